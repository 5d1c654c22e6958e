#pragma once

#include "base/rt_stall_pipe.h"
#include "base/rt_value.h"
#include "golden/quadric.h"
#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// rt_quadric_model: the cycle model of rt_quadric, cycle for cycle and bit for
// bit at its ports, as rt_isect_model is rt_isect's: QUADRIC_LATENCY stages
// with the RTL's stage control (base/rt_stall_pipe.h); the entry stage
// computes the whole result with fx::intersectQuadric() (the golden model)
// and the other stages only carry it. Plain C++ on value ports, stepped by the
// run loop (sw/driver/isect_run.h): set the inputs, settle() for req_ready_o,
// clock() at the rising edge.
struct rt_quadric_model : rt_pipe_model<rt_quadric_model, rt_quadric_ports<rt_value, rt_value, value_t>,
                                         QUADRIC_LATENCY, ISECT_RES_W> {
  // The entry stage: the golden result of the request on the ports, into `out`.
  void compute(res_t& out);
};

}  // namespace lancer::sc
