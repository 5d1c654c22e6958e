#pragma once

// What every integrator asks of a scene's lights (docs/effects.md): its area
// lights (emissive triangles), the way to a point, spot or directional light,
// and points spread uniformly over a triangle.

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace lancer {

// An emissive triangle, lit on the side of its geometric normal.
struct Emitter {
  uint32_t prim;
  glm::vec3 normal;  // unit geometric normal: the side it emits on
  float area;
  glm::vec3 emission;
};

// The scene's emissive triangles of non-zero area, in triangle order.
std::vector<Emitter> emittersOf(const Scene& scene);

// The way from `point` to a point, spot or directional light: the unit
// direction, the distance (infinite for a directional light) and the light's
// colour scaled by a spot's cone; nullopt where no light arrives (the light
// at the point itself, or outside a spot's outer cone).
struct LightPath {
  glm::vec3 dir;
  float distance;
  glm::vec3 color;
};
std::optional<LightPath> pathToLight(const Light& light, const glm::vec3& point);

// A point of the triangle from two uniform numbers, uniform over its area.
inline glm::vec3 pointOnTriangle(const Triangle& t, glm::vec2 u) {
  const float r = std::sqrt(u.x);
  return (1.0f - r) * t.v0 + r * (1.0f - u.y) * t.v1 + r * u.y * t.v2;
}

}  // namespace lancer
