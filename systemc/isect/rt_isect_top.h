#pragma once

#include <memory>
#include <string>

#include <systemc>

#include "base/rt_fst_wave.h"
#include "isect/rt_isect_rtl.h"
#include "isect/rt_pipe_kind.h"
#include "isect/rt_pipe_tb.h"

namespace lancer::sc {

// rt_isect_top: the SystemC system of the intersection path: rt_isect and
// rt_quadric, each in both implementations, each implementation on its own
// testbench and gated clock (rt_pipe_bench), because SystemC elaborates once
// per process: nothing can be instantiated after the first sc_start(). A run
// clocks only the bench it uses.
//
// The Verilated RTL is present only when the build had the RTL sources
// (LANCER_RTL_ISECT_SOURCES, LANCER_RTL_QUADRIC_SOURCES); has_rtl() says so.
SC_MODULE(rt_isect_top) {
  explicit rt_isect_top(sc_core::sc_module_name name);
  ~rt_isect_top() override;

  static bool has_rtl();
  static bool has_waves();  // the Verilated RTL was built with --trace-fst

  // The testbench of a pipeline's implementation; throws std::runtime_error for rtl if absent.
  template <class Kind>
  rt_pipe_tb<Kind>& tb(rt_isect_impl impl);

  // FST waveform of a pipeline's Verilated RTL bench (its ports and
  // internals), from now until close_wave(). Call while the simulation is paused.
  template <class Kind>
  void open_wave(const std::string& path);
  void close_wave();

 private:
  template <class Kind>
  struct benches {
    std::unique_ptr<sc_core::sc_module> model, rtl;
    rt_pipe_tb<Kind>* model_tb = nullptr;
    rt_pipe_tb<Kind>* rtl_tb = nullptr;
  };
  template <class Kind>
  benches<Kind>& of();

  benches<isect_kind> isect_;
  benches<quadric_kind> quadric_;
  rt_fst_wave wave_;
};

}  // namespace lancer::sc
