#include "isect/rt_isect_model.h"

#include "golden/isect.h"

namespace lancer::sc {

rt_isect_model::rt_isect_model(sc_core::sc_module_name name)
    : sc_core::sc_module(name) {
  SC_METHOD(seq);
  sensitive << clk_i.pos() << rst_ni.neg();
  dont_initialize();

  SC_METHOD(comb);
  sensitive << res_ready_i << state_changed_;
}

std::array<bool, rt_isect_model::NUM_STAGES> rt_isect_model::stageReady() const {
  std::array<bool, NUM_STAGES> ready{};
  ready[NUM_STAGES - 1] = !valid_q_[NUM_STAGES - 1] || res_ready_i.read();
  for (int s = NUM_STAGES - 2; s >= 0; --s) ready[size_t(s)] = !valid_q_[size_t(s)] || ready[size_t(s) + 1];
  return ready;
}

isect_res_t rt_isect_model::compute() const {
  // Fixed-size wire images: no allocation per request.
  fx::RayWire rayWire;
  fx::TriWire triWire;
  fx::ResWire resWire;
  fromPort<ISECT_RAY_W>(req_ray_i.read(), rayWire);
  fromPort<ISECT_TRI_W>(req_tri_i.read(), triWire);
  fx::QRay ray;
  fx::QTriangle tri;
  fx::unpackRay(rayWire, ray);
  fx::unpackTriangle(triWire, tri);
  fx::packWire(fx::intersect(ray, tri), resWire);
  return toPort<ISECT_RES_W>(resWire);
}

void rt_isect_model::seq() {
  if (!rst_ni.read()) {
    valid_q_.fill(false);
  } else {
    // All loads use the registers as they were before this edge: walk from the
    // output back to the entry so that stage s-1 is read before it is written.
    const std::array<bool, NUM_STAGES> ready = stageReady();
    for (size_t s = NUM_STAGES - 1; s > 0; --s) {
      if (!ready[s]) continue;  // stalled: holds its item
      if (valid_q_[s - 1]) data_q_[s] = data_q_[s - 1];
      valid_q_[s] = valid_q_[s - 1];
    }
    if (ready[0]) {
      const bool load = req_valid_i.read();
      if (load) data_q_[0] = compute();
      valid_q_[0] = load;
    }
  }
  res_valid_o.write(valid_q_[NUM_STAGES - 1]);
  res_data_o.write(data_q_[NUM_STAGES - 1]);
  state_changed_.notify();  // immediate: comb() runs in this evaluation phase
}

void rt_isect_model::comb() { req_ready_o.write(stageReady()[0]); }

}  // namespace lancer::sc
