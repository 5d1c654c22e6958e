#pragma once

#include <memory>
#include <string>

#include <systemc>

#include "grid/rt_grid_mem.h"
#include "grid/rt_grid_tb.h"

namespace lancer::sc {

enum class rt_grid_impl {
  model,            // rt_grid_model with rt_isect_model inside: all hand-written cycle models
  model_rtl_isect,  // rt_grid_model with the Verilated Vrt_isect_sc inside (mixed)
  rtl,              // Vrt_grid_sc: rtl/grid/rt_grid.sv (with its rt_isect) Verilated with --sc
};

// rt_grid_top: the SystemC system of the grid unit: traversal unit ->
// intersection pipeline (inside the traversal unit, as in the RTL) -> memory
// (rt_grid_mem), fed and drained by rt_grid_tb. One bench per implementation,
// each with its own gated clock, because SystemC elaborates once per process;
// a run clocks only the bench it uses. has_rtl() / has_rtl_isect() say which
// Verilated models the build has.
SC_MODULE(rt_grid_top) {
  explicit rt_grid_top(sc_core::sc_module_name name);
  ~rt_grid_top() override;

  static bool has_rtl();        // Vrt_grid_sc (LANCER_RTL_GRID_SOURCES)
  static bool has_rtl_isect();  // Vrt_isect_sc (LANCER_RTL_ISECT_SOURCES)
  static bool has_waves();      // Vrt_grid_sc built with FST tracing

  // Makes the SystemC systems' own VerilatedContext the thread's current one
  // (created on first call). A VerilatedContext sets itself current when
  // constructed and leaves a dangling pointer when destroyed, so a C++
  // Verilated device (sw/driver/verilator_*_device) created and destroyed
  // before the Verilated SystemC models are built, or between their runs,
  // would otherwise leave them a deleted context. Called before elaboration
  // and before every run (sw/driver/systemc_kernel.cpp). No-op without RTL.
  static void use_verilated_context();

  // Throws std::runtime_error for an implementation the build lacks.
  rt_grid_tb& tb(rt_grid_impl impl);
  rt_grid_mem& mem(rt_grid_impl impl);

  // FST waveform of the Verilated rt_grid bench until close_wave(); call while paused.
  void open_wave(const std::string& path);
  void close_wave();

 private:
  struct bench_refs {
    std::unique_ptr<sc_core::sc_module> bench;
    rt_grid_tb* tb = nullptr;
    rt_grid_mem* mem = nullptr;
  };
  struct wave;
  bench_refs& refs(rt_grid_impl impl);
  bench_refs model_, mixed_, rtl_;
  std::unique_ptr<wave> wave_;
};

}  // namespace lancer::sc
