#pragma once

#include <memory>
#include <string>

#include <systemc>

#include "octree/rt_octree_mem.h"
#include "octree/rt_octree_tb.h"

namespace lancer::sc {

enum class rt_octree_impl {
  model,  // rt_octree_model: the hand-written cycle model (rt_isect's timing inside)
  rtl,    // Vrt_octree_sc: rtl/octree/rt_octree.sv (with its rt_isect) Verilated with --sc
};

// rt_octree_top: the SystemC system of the octree unit: traversal unit ->
// memory (rt_octree_mem), fed and drained by rt_octree_tb. One bench per
// implementation, each with its own gated clock, because SystemC elaborates
// once per process; a run clocks only the bench it uses. Built by
// sw/driver/systemc_kernel.cpp after rt_grid_top, whose
// use_verilated_context() gives the Verilated model its VerilatedContext.
SC_MODULE(rt_octree_top) {
  explicit rt_octree_top(sc_core::sc_module_name name);
  ~rt_octree_top() override;

  static bool has_rtl();    // Vrt_octree_sc (LANCER_RTL_OCTREE_SOURCES)
  static bool has_waves();  // Vrt_octree_sc built with FST tracing

  // Throws std::runtime_error for an implementation the build lacks.
  rt_octree_tb& tb(rt_octree_impl impl);
  rt_octree_mem& mem(rt_octree_impl impl);

  // FST waveform of the Verilated rt_octree bench until close_wave(); call while paused.
  void open_wave(const std::string& path);
  void close_wave();

 private:
  struct bench_refs {
    std::unique_ptr<sc_core::sc_module> bench;
    rt_octree_tb* tb = nullptr;
    rt_octree_mem* mem = nullptr;
  };
  struct wave;
  bench_refs& refs(rt_octree_impl impl);
  bench_refs model_, rtl_;
  std::unique_ptr<wave> wave_;
};

}  // namespace lancer::sc
