#pragma once

// The scene's primitives as the float structures store and test them, in the
// scene's one id space (scene.h): triangles 0 .. T-1 by the watertight test,
// quadric i (id T + i) by the float reference's quadric test. A structure
// bins a primitive by primitiveBounds() and tests it with intersectPrimitive();
// one of triangles only keeps its own triangle-only loop (the structures pick
// it when the scene has no quadrics), so a triangle scene runs the code it ran
// before quadrics existed.

#include <cstdint>
#include <optional>

#include "ref/accel.h"
#include "ref/quadric.h"
#include "ref/triangle.h"
#include "scene/scene.h"

namespace lancer {

// The box a structure bins primitive `prim` by: a triangle's vertices' box, a
// quadric's Quadric::bounds() (rounded outwards).
inline Aabb primitiveBounds(const Scene& scene, uint32_t prim) {
  return scene.isQuadric(prim) ? scene.quadricOf(prim).bounds() : scene.triangles[prim].bounds();
}

// The float reference's hit of a quadric as a Hit (u = 0 entering, 1 leaving).
inline std::optional<Hit> intersectQuadricHit(const Ray& ray, const QuadricShape& shape, uint32_t prim) {
  const std::optional<QuadricHit> hit = intersectQuadric(ray, shape, prim);
  return hit ? std::optional<Hit>(hit->hit) : std::nullopt;
}

// Closest-hit test of primitive `prim` of `scene` (`wray` is `ray`'s
// watertight constants): the triangle's or the quadric's test, t in
// (0, ray.tMax]; the structures keep the closest by closerHit(), the
// triangles' tie rule (an exact tie to the lower id).
inline std::optional<Hit> intersectPrimitive(const Scene& scene, const WatertightRay& wray, const Ray& ray,
                                             uint32_t prim) {
  if (!scene.isQuadric(prim)) return intersectTriangle(wray, scene.triangles[prim], prim);
  return intersectQuadricHit(ray, QuadricShape::of(scene.quadricOf(prim)), prim);
}

// intersectPrimitive() counted in `stats` (if any) by its kind, for a
// structure's leaf loop: kQuadrics false (a scene of triangles only) is the
// triangle test alone, as before quadrics.
template <bool kQuadrics>
std::optional<Hit> intersectCounted(const Scene& scene, const WatertightRay& wray, const Ray& ray, uint32_t prim,
                                    TraversalStats* stats) {
  if constexpr (kQuadrics) {
    if (stats) ++(scene.isQuadric(prim) ? stats->quadricTests : stats->triangleTests);
    return intersectPrimitive(scene, wray, ray, prim);
  } else {
    if (stats) ++stats->triangleTests;
    return intersectTriangle(wray, scene.triangles[prim], prim);
  }
}

// The unit geometric normal of primitive `prim` at `point` (a point of its
// surface): a triangle's (v1 - v0) x (v2 - v0) normalized, zero for a
// degenerate one; a quadric's outward normal (out of the solid of |radius|,
// whatever the sign of an NFF radius: quadricNormal()).
glm::vec3 geometricNormal(const Scene& scene, uint32_t prim, const glm::vec3& point);

}  // namespace lancer
