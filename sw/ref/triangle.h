#pragma once

#include <optional>

#include "common/ray.h"
#include "scene/scene.h"

namespace lancer {

// Per-ray constants of the watertight ray-triangle test of Woop, Benthin and
// Wald (JCGT 2013). Computed once per ray, shared by every triangle test.
struct WatertightRay {
  glm::vec3 origin;
  glm::vec3 dir;  // for the hit distance (the plane equation, in double)
  int kx = 0, ky = 1, kz = 2;  // kz: the dominant axis of the direction
  float sx = 0, sy = 0;  // shear taking the direction onto the kz axis
  float tMax = kInfinity;

  explicit WatertightRay(const Ray& ray);
};

// Index of the largest |component|; ties go to the lower axis (x before y before z).
// The fixed-point models use the same rule so every layer picks the same axis.
int dominantAxis(const glm::vec3& v);

// Closest-hit test of one triangle; nullopt on a miss or for t outside (0, tMax].
// Watertight: a ray through a shared edge or vertex of a closed mesh hits at
// least one of the triangles that share it, because the edge functions of a
// shared edge are computed from the same sheared vertices (bit-identical inputs)
// and fall back to double precision when they round to zero. The hit distance
// comes from the plane equation in double, accurate on slivers too.
std::optional<Hit> intersectTriangle(const WatertightRay& ray, const Triangle& tri,
                                     uint32_t prim);

// The same test evaluated in long double, the "higher-precision re-test" used to
// arbitrate disagreements with other tracers.
std::optional<Hit> intersectTriangleExtended(const Ray& ray, const Triangle& tri,
                                             uint32_t prim);

}  // namespace lancer
