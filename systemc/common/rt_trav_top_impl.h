#pragma once

// The members of rt_trav_top<Unit>, for the unit's rt_<unit>_system.cpp to
// instantiate once it has named its Verilated class:
//   template <> struct rt_trav_rtl<rt_grid_unit> { using type = Vrt_grid_sc; };  // when built
//   template class rt_trav_top<rt_grid_unit>;
// Compiled inside lancer_systemc, with its LANCER_SC_* definitions.

#include <stdexcept>
#include <type_traits>
#include <utility>

#include "common/rt_trav_bench.h"
#include "common/rt_trav_pin_model.h"
#include "common/rt_trav_top.h"
#include "isect/rt_isect_rtl.h"

#if LANCER_SC_HAVE_GRID_RTL || LANCER_SC_HAVE_OCTREE_RTL
#include "verilated.h"
#if LANCER_SC_RTL_FST
#include "verilated_fst_sc.h"
#endif
#endif

namespace lancer::sc {

// Whether the unit's cycle model can hold the Verilated rt_isect (a constructor
// taking an rt_isect_impl, as rt_grid_model's): the mixed implementation.
template <class Unit>
inline constexpr bool kModelTakesIsect = std::is_constructible_v<typename Unit::model_t, rt_isect_impl>;

template <class Unit>
template <class Dut, class... DutArgs>
void rt_trav_top<Unit>::keep(bench_refs& r, const char* name, DutArgs&&... args) {
  auto bench = std::make_unique<rt_trav_bench<Unit, Dut>>(name, kScChipUnits, std::forward<DutArgs>(args)...);
  r.tb = &bench->u_tb;
  r.bench = std::move(bench);
}

template <class Unit>
rt_trav_top<Unit>::rt_trav_top(sc_core::sc_module_name name) : sc_core::sc_module(name) {
  using rtl_t = typename rt_trav_rtl<Unit>::type;
  use_verilated_context();
  keep<rt_trav_pin_model<Unit>>(model_, "u_model");
  if constexpr (kModelTakesIsect<Unit>) {
    if (has_rtl_isect()) keep<rt_trav_pin_model<Unit>>(mixed_, "u_mixed", rt_isect_impl::rtl);
  }
  if constexpr (!std::is_void_v<rtl_t>) {
    if (rt_fst_wave::available()) Verilated::traceEverOn(true);  // before the Verilated model is built
    keep<rtl_t>(rtl_, "u_rtl");
  }
}

template <class Unit>
rt_trav_top<Unit>::~rt_trav_top() = default;

template <class Unit>
bool rt_trav_top<Unit>::has_rtl() {
  return !std::is_void_v<typename rt_trav_rtl<Unit>::type>;
}

template <class Unit>
bool rt_trav_top<Unit>::has_rtl_isect() {
  return kModelTakesIsect<Unit> && LANCER_SC_HAVE_RTL != 0;
}

template <class Unit>
bool rt_trav_top<Unit>::has_waves() {
  return has_rtl() && rt_fst_wave::available();
}

template <class Unit>
typename rt_trav_top<Unit>::bench_refs& rt_trav_top<Unit>::refs(rt_trav_impl impl) {
  bench_refs& r = impl == rt_trav_impl::model ? model_ : (impl == rt_trav_impl::rtl ? rtl_ : mixed_);
  if (r.tb == nullptr) {
    throw std::runtime_error(std::string("this implementation of ") + Unit::kNames.module +
                             " is not part of the build (no Verilated RTL)");
  }
  return r;
}

template <class Unit>
typename rt_trav_top<Unit>::tb_t& rt_trav_top<Unit>::tb(rt_trav_impl impl) {
  return *refs(impl).tb;
}

template <class Unit>
void rt_trav_top<Unit>::open_wave([[maybe_unused]] const std::string& path) {
  using rtl_t = typename rt_trav_rtl<Unit>::type;
  if constexpr (std::is_void_v<rtl_t> || !LANCER_SC_RTL_FST) {
    throw std::runtime_error(std::string("the Verilated ") + Unit::kNames.module + " of this build has no FST tracing");
  } else {
    // Verilator's trace() needs elaboration complete: the first run of the process
    // may ask for a wave. Zero time with every clock at rest changes nothing.
    if (!sc_core::sc_start_of_simulation_invoked()) sc_core::sc_start(sc_core::SC_ZERO_TIME);
    auto& dut = *static_cast<rt_trav_bench<Unit, rtl_t>*>(rtl_.bench.get())->duts.front();  // unit 0's
    wave_.open(path, [&dut](VerilatedFstSc* fst) { dut.trace(fst, 99); });
  }
}

template <class Unit>
void rt_trav_top<Unit>::close_wave() {
  wave_.close();
}

}  // namespace lancer::sc
