#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "common/ray.h"
#include "scene/scene.h"

namespace lancer {

// A ray's hit as the integrators shade it: the point, the normals, the side.
struct SurfacePoint {
  const Material& material;
  glm::vec3 point;      // from the barycentrics: on the triangle's plane to float rounding
  glm::vec3 dir;        // the ray's unit direction
  glm::vec3 geometric;  // unit geometric normal (-dir for a degenerate triangle)
  glm::vec3 normal;     // shading normal, turned to the side the ray arrives on
  bool front;           // the ray arrives on the geometric normal's side

  // The side of the geometric normal a ray leaving here along `d` leaves on
  // (WaveRay::side): +1 front, -1 back; exactly in the plane, the side the
  // arriving ray came from.
  int8_t sideOf(const glm::vec3& d) const {
    const float side = glm::dot(d, geometric);
    return side > 0.0f ? 1 : side < 0.0f ? -1 : (front ? 1 : -1);
  }
};

// The shading normal is Scene::normals interpolated with the hit's
// barycentrics (NFF `pp`, tessellated spheres and cones), else the geometric
// normal (SPD rule 3); both are turned to the side the ray arrives on, so an
// opaque triangle hit from behind shades as if two-sided (docs/effects.md).
SurfacePoint surfaceAt(const Scene& scene, const Ray& ray, const Hit& hit);

}  // namespace lancer
