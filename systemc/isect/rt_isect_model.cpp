#include "isect/rt_isect_model.h"

#include <span>

#include "golden/isect.h"

namespace lancer::sc {

namespace {

// A value port's wire image: in place for the wide records, else through `scratch`.
template <int W>
std::span<const uint32_t> wireIn(const value_t<W>& v, std::span<uint32_t> scratch) {
  if constexpr (W > 64) {
    return wireOf<W>(v);
  } else {
    fromValue<W>(v, scratch);
    return scratch;
  }
}

// A result into a value port: in place for the wide records.
template <int W>
void packInto(const fx::IsectResult& result, value_t<W>& out) {
  if constexpr (W > 64) {
    fx::packWire(result, out);  // packing clears the bits above the record
  } else {
    fx::ResWire wire{};
    fx::packWire(result, wire);
    out = toValue<W>(wire);
  }
}

}  // namespace

std::array<bool, rt_isect_model::NUM_STAGES> rt_isect_model::stageReady() const {
  std::array<bool, NUM_STAGES> ready{};
  ready[NUM_STAGES - 1] = !valid_q_[NUM_STAGES - 1] || res_ready_i.value;
  for (int s = NUM_STAGES - 2; s >= 0; --s) ready[size_t(s)] = !valid_q_[size_t(s)] || ready[size_t(s) + 1];
  return ready;
}

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

void rt_isect_model::reset() {
  valid_q_.fill(false);
  writeOutputs();
  settle();
}

void rt_isect_model::settle() { req_ready_o = stageReady()[0]; }

void rt_isect_model::clock() {
  // All loads use the registers as they were before this edge: walk from the
  // output back to the entry so that stage s-1 is read before it is written.
  const std::array<bool, NUM_STAGES> ready = stageReady();
  for (size_t s = NUM_STAGES - 1; s > 0; --s) {
    if (!ready[s]) continue;  // stalled: holds its item
    if (valid_q_[s - 1]) data_q_[s] = data_q_[s - 1];
    valid_q_[s] = valid_q_[s - 1];
  }
  if (ready[0]) {
    const bool load = req_valid_i.value;
    if (load) compute(data_q_[0]);
    valid_q_[0] = load;
  }
  writeOutputs();
  settle();
}

void rt_isect_model::writeOutputs() {
  res_valid_o = valid_q_[NUM_STAGES - 1];
  res_data_o = data_q_[NUM_STAGES - 1];
}

}  // namespace lancer::sc
