#pragma once

#include <array>

#include "base/rt_stall_pipe.h"
#include "base/rt_value.h"
#include "golden/records.h"
#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// rt_isect_model: hand-written cycle model of rtl/isect/rt_isect.sv, meant to
// match it cycle for cycle and bit for bit at its ports.
//
// Latency:    ISECT_LATENCY (= fx::kIsectLatency) register stages: a request
//             accepted at an edge shows on res_valid_o ISECT_LATENCY - 1 edges
//             later, i.e. it is taken at the earliest ISECT_LATENCY cycles after
//             the cycle it was accepted in.
// Throughput: one request per cycle. Backpressure exactly as the RTL
//             (base/rt_stall_pipe.h): req_ready_o depends combinationally on
//             res_ready_i; res_valid_o / res_data_o come from the last stage
//             register.
// Reset:      clears the valid bits; the data registers are not reset and load
//             only with a valid item (as the RTL's).
//
// The arithmetic is not duplicated: the entry stage computes the whole result
// with fx::intersect() (the golden model) and the other stages only carry it.
//
// Plain C++ on value ports (base/rt_value.h), under the RTL's names: the run
// loop clocks it directly (the fast path, sw/driver/isect_run.h), and
// rt_pipe_pin_model binds it to sc_in/sc_out. The caller orders evaluation:
// set the inputs, settle() for req_ready_o, clock() at the rising edge.
struct rt_isect_model
    : rt_pipe_model<rt_isect_model, rt_isect_ports<rt_value, rt_value, value_t>, ISECT_LATENCY, ISECT_RES_W> {
  // The entry stage: the golden result of the request on the ports, into `out`.
  void compute(res_t& out);

 private:
  // The last request's ray, unpacked: a ray meets its candidate triangles in a
  // row, and unpacking it each time cost a tenth of the fast path's time.
  value_t<ISECT_RAY_W> rayPort_{};
  fx::QRay ray_{};
  bool rayValid_ = false;
};

}  // namespace lancer::sc
