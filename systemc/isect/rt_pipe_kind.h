#pragma once

// The intersection path's two pipelines as one parameter of its SystemC system
// (the testbench rt_pipe_tb, the pin-level model rt_pipe_pin_model, the bench
// rt_pipe_bench, rt_isect_top): rt_isect takes a triangle on req_tri_i,
// rt_quadric a sphere or cone record on req_quadric_i; their other ports
// (rt_stream_ports), their stage control and their result records are the same.

#include "isect/rt_isect_model.h"
#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_types.h"
#include "isect/rt_quadric_model.h"

namespace lancer::sc {

template <template <template <class> class, template <class> class, template <int> class> class Ports, class Model,
          int PrimW>
struct rt_pipe_kind {
  static constexpr int PRIM_W = PrimW;  // the primitive port's width
  template <template <class> class In, template <class> class Out, template <int> class Bits = vl_port_t>
  using ports = Ports<In, Out, Bits>;
  using model = Model;  // the cycle model on value ports
};

// Each kind names its primitive's port: prim(x) of a module, a model or signals.
struct isect_kind : rt_pipe_kind<rt_isect_ports, rt_isect_model, ISECT_TRI_W> {
  static auto& prim(auto& ports) { return ports.req_tri_i; }
};
struct quadric_kind : rt_pipe_kind<rt_quadric_ports, rt_quadric_model, ISECT_QUADRIC_W> {
  static auto& prim(auto& ports) { return ports.req_quadric_i; }
};

}  // namespace lancer::sc
