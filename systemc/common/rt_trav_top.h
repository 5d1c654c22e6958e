#pragma once

#include <memory>
#include <string>

#include <systemc>

#include "base/rt_fst_wave.h"
#include "common/rt_trav_tb.h"

namespace lancer::sc {

enum class rt_trav_impl {
  model,            // the unit's hand-written cycle model (Unit::model_t), rt_isect's cycle model or timing inside
  model_rtl_isect,  // the cycle model with the Verilated Vrt_isect_sc inside (mixed, when the model takes it)
  rtl,              // the unit's RTL (with its rt_isect) Verilated with --sc (rt_trav_rtl<Unit>)
};

// Makes the SystemC systems' own VerilatedContext the thread's current one
// (created on first call). A VerilatedContext sets itself current when
// constructed and leaves a dangling pointer when destroyed, so a C++
// Verilated device (sw/driver/verilator_*_device) created and destroyed
// before the Verilated SystemC models are built, or between their runs,
// would otherwise leave them a deleted context. Called before elaboration
// and before every run (sw/driver/systemc_kernel.cpp). No-op without RTL.
void use_verilated_context();

// The units a SystemC chip is elaborated with (CMake LANCER_SC_CHIP_UNITS):
// SystemC elaborates once per process, so every bench holds this many units,
// and a run clocks only the ones it uses.
#ifndef LANCER_SC_CHIP_UNITS
#define LANCER_SC_CHIP_UNITS 16
#endif
inline constexpr int kScChipUnits = LANCER_SC_CHIP_UNITS;

// rt_trav_top: the SystemC system of a traversal unit (Unit: its traits,
// common/rt_trav_unit.h): a chip of kScChipUnits traversal units (each with
// its intersection pipeline inside, as in the RTL) on the chip's memory
// system, fed and drained by rt_trav_tb. One bench (rt_trav_bench) per
// implementation, each unit with its own gated clock, because SystemC
// elaborates once per process; a run clocks only the units it uses.
// Its members are defined in common/rt_trav_top_impl.h and instantiated by the
// unit's systemc/<unit>/rt_<unit>_system.cpp, the one file that includes its
// Verilated class.
template <class Unit>
class rt_trav_top : public sc_core::sc_module {
 public:
  using tb_t = rt_trav_tb<Unit>;

  explicit rt_trav_top(sc_core::sc_module_name name);
  ~rt_trav_top() override;

  static bool has_rtl();        // the unit's Verilated class
  static bool has_rtl_isect();  // the mixed implementation (Vrt_isect_sc, a model that takes it)
  static bool has_waves();      // the unit's Verilated class built with FST tracing

  // Throws std::runtime_error for an implementation the build lacks.
  tb_t& tb(rt_trav_impl impl);

  // FST waveform of the Verilated bench until close_wave(); call while paused.
  void open_wave(const std::string& path);
  void close_wave();

 private:
  struct bench_refs {
    std::unique_ptr<sc_core::sc_module> bench;
    tb_t* tb = nullptr;
  };
  bench_refs& refs(rt_trav_impl impl);
  template <class Dut, class... DutArgs>
  void keep(bench_refs& r, const char* name, DutArgs&&... args);
  bench_refs model_, mixed_, rtl_;
  rt_fst_wave wave_;
};

}  // namespace lancer::sc
