#include "isect/rt_isect_model.h"

#include <span>

#include "golden/isect.h"

namespace lancer::sc {

void rt_isect_model::compute(res_t& out) {
  // Fixed-size wire images: no allocation per request.
  if (!rayValid_ || !(req_ray_i.value == rayPort_)) {
    fx::RayWire rayWire{};
    fx::unpackRay(wireIn<ISECT_RAY_W>(req_ray_i.value, rayWire), ray_);
    rayPort_ = req_ray_i.value;
    rayValid_ = true;
  }
  fx::TriWire triWire{};
  fx::QTriangle tri;
  fx::unpackTriangle(wireIn<ISECT_TRI_W>(req_tri_i.value, triWire), tri);
  packInto<ISECT_RES_W>(fx::intersect(ray_, tri), out);
}

}  // namespace lancer::sc
