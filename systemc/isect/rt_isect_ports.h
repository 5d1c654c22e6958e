#pragma once

// rt_isect's and rt_quadric's request and result streams, declared once for
// each side that meets them: In and Out are what rt_isect's inputs and outputs are there —
// <sc_in, sc_out> in the cycle model, <sc_out, sc_in> in the testbench,
// <sc_signal, sc_signal> in a bench or a traversal unit that holds rt_isect,
// <rt_value, rt_value, value_t> (plain values) in a cycle model stepped directly.
// Clock and reset are each side's own (a bench's signals, a unit's ports).

#include <systemc>

#include "isect/rt_isect_types.h"

namespace lancer::sc {

// What both pipelines' ports share: everything but the primitive's.
template <template <class> class In, template <class> class Out, template <int> class Bits = vl_port_t>
struct rt_stream_ports {
  // Requests: one ray-primitive pair per transfer.
  In<bool> req_valid_i{"req_valid_i"};
  Out<bool> req_ready_o{"req_ready_o"};
  In<Bits<ISECT_RAY_W>> req_ray_i{"req_ray_i"};

  // Results, in request order.
  Out<bool> res_valid_o{"res_valid_o"};
  In<bool> res_ready_i{"res_ready_i"};
  Out<Bits<ISECT_RES_W>> res_data_o{"res_data_o"};
};

// rt_isect's: a triangle with the ray.
template <template <class> class In, template <class> class Out, template <int> class Bits = vl_port_t>
struct rt_isect_ports : rt_stream_ports<In, Out, Bits> {
  In<Bits<ISECT_TRI_W>> req_tri_i{"req_tri_i"};
};

// rt_quadric's (rtl/isect/rt_quadric.sv): a sphere or cone record with the ray.
template <template <class> class In, template <class> class Out, template <int> class Bits = vl_port_t>
struct rt_quadric_ports : rt_stream_ports<In, Out, Bits> {
  In<Bits<ISECT_QUADRIC_W>> req_quadric_i{"req_quadric_i"};
};

// sc_signal under one template parameter, for the In/Out of a port list.
template <class T>
using rt_signal = sc_core::sc_signal<T>;

using rt_isect_signals = rt_isect_ports<rt_signal, rt_signal>;

// Binds the ports both pipelines have (all but the primitive's) to signals of
// the same names.
template <class M, class Signals>
void bindStreamPorts(M& m, Signals& s) {
  m.req_valid_i(s.req_valid_i);
  m.req_ready_o(s.req_ready_o);
  m.req_ray_i(s.req_ray_i);
  m.res_valid_o(s.res_valid_o);
  m.res_ready_i(s.res_ready_i);
  m.res_data_o(s.res_data_o);
}

// Binds a module's rt_isect ports (the cycle model's, the testbench's, the
// Verilated class's: the same names) to signals of the same names.
template <class M, class Signals>
void bindIsectPorts(M& m, Signals& s) {
  bindStreamPorts(m, s);
  m.req_tri_i(s.req_tri_i);
}

}  // namespace lancer::sc
