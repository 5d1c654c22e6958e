#pragma once

// The intersection path's two pipelines as one parameter of its SystemC system
// (the testbench rt_pipe_tb, the pin-level model rt_pipe_pin_model, the bench
// rt_pipe_bench, rt_isect_top): rt_isect takes a triangle on req_tri_i,
// rt_quadric a sphere or cone record on req_quadric_i; their other ports, their
// stage control and their result records are the same.

#include "isect/rt_isect_model.h"
#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_types.h"
#include "isect/rt_quadric_model.h"

namespace lancer::sc {

struct isect_kind {
  static constexpr int PRIM_W = ISECT_TRI_W;
  template <template <class> class In, template <class> class Out, template <int> class Bits = vl_port_t>
  using ports = rt_isect_ports<In, Out, Bits>;
  using model = rt_isect_model;
  template <class Ports>
  static auto& prim(Ports& p) { return p.req_tri_i; }
  template <class M, class Signals>
  static void bind(M& m, Signals& s) { bindIsectPorts(m, s); }
};

struct quadric_kind {
  static constexpr int PRIM_W = ISECT_QUADRIC_W;
  template <template <class> class In, template <class> class Out, template <int> class Bits = vl_port_t>
  using ports = rt_quadric_ports<In, Out, Bits>;
  using model = rt_quadric_model;
  template <class Ports>
  static auto& prim(Ports& p) { return p.req_quadric_i; }
  template <class M, class Signals>
  static void bind(M& m, Signals& s) { bindQuadricPorts(m, s); }
};

}  // namespace lancer::sc
