#include "isect/rt_quadric_model.h"

#include <array>
#include <span>

namespace lancer::sc {

void rt_quadric_model::compute(res_t& out) {
  std::array<uint32_t, fx::kIsectRayWords> rayWire{};
  std::array<uint32_t, size_t(fx::wireWords(ISECT_QUADRIC_W))> quadricWire{};
  const fx::QRay ray = fx::unpackRay(wireIn<ISECT_RAY_W>(req_ray_i.value, rayWire));
  const fx::QQuadric quadric = fx::unpackQuadric(wireIn<ISECT_QUADRIC_W>(req_quadric_i.value, quadricWire));
  packInto<ISECT_RES_W>(fx::intersectQuadric(ray, quadric), out);
}

}  // namespace lancer::sc
