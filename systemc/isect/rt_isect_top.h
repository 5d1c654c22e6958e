#pragma once

#include <memory>
#include <string>

#include <systemc>

#include "base/rt_fst_wave.h"
#include "isect/rt_isect_rtl.h"
#include "isect/rt_isect_tb.h"

namespace lancer::sc {

// rt_isect_top: the SystemC system of the intersection pipeline. It holds both
// implementations, each on its own testbench and gated clock (rt_isect_bench),
// because SystemC elaborates once per process: nothing can be instantiated after
// the first sc_start(). A run clocks only the bench it uses.
//
// The Verilated RTL is present only when the build had the RTL sources
// (LANCER_RTL_ISECT_SOURCES); has_rtl() says so.
SC_MODULE(rt_isect_top) {
  explicit rt_isect_top(sc_core::sc_module_name name);
  ~rt_isect_top() override;

  static bool has_rtl();
  static bool has_waves();  // the Verilated RTL was built with --trace-fst

  // The testbench of an implementation; throws std::runtime_error for rtl if absent.
  rt_isect_tb& tb(rt_isect_impl impl);

  // FST waveform of the Verilated RTL bench (its ports and internals), from now
  // until close_wave(). Call while the simulation is paused.
  void open_wave(const std::string& path);
  void close_wave();

 private:
  std::unique_ptr<sc_core::sc_module> model_;
  std::unique_ptr<sc_core::sc_module> rtl_;
  rt_isect_tb* model_tb_ = nullptr;
  rt_isect_tb* rtl_tb_ = nullptr;
  rt_fst_wave wave_;
};

}  // namespace lancer::sc
