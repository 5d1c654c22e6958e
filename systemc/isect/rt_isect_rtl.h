#pragma once

#include <memory>

#include <systemc>

#include "isect/rt_isect_ports.h"

namespace lancer::sc {

// Which rt_isect a traversal unit's cycle model holds.
enum class rt_isect_impl {
  model,  // the hand-written cycle model (rt_isect_model, or its timing inside the unit's model)
  rtl,    // Vrt_isect_sc, rtl/isect/rt_isect.sv Verilated with --sc
};

// The Verilated rt_isect on a clock, a reset and signals, for a unit's cycle
// model that holds it (the mixed system); throws std::runtime_error when the
// build lacks it. Here, so that only lancer_systemc sees the Verilated class.
std::unique_ptr<sc_core::sc_module> make_rtl_isect(const char* name, sc_core::sc_in<bool>& clk,
                                                   sc_core::sc_in<bool>& rst, rt_isect_signals& s);

}  // namespace lancer::sc
