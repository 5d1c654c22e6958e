#pragma once

// The port types of rt_grid as SystemC sees them, shared by the hand-written
// cycle model (rt_grid_model), the Verilated RTL (Vrt_grid_sc), the memory
// model and the testbench, so that either implementation drops into the same
// sockets. Widths and Verilator's type mapping as in isect/rt_isect_types.h
// (vl_port_t<W>: bool, uint32_t, uint64_t, sc_bv<W>).

#include <cstdint>

#include "common/rt_trav_unit.h"
#include "golden/records.h"
#include "isect/rt_isect_types.h"

#ifndef LANCER_GRID_RAYS_IN_FLIGHT
#error "LANCER_GRID_RAYS_IN_FLIGHT must come from the build (rtl/CMakeLists.txt, systemc/CMakeLists.txt)"
#endif
#ifndef LANCER_GRID_CELL_QUEUE
#error "LANCER_GRID_CELL_QUEUE must come from the build (rtl/CMakeLists.txt, systemc/CMakeLists.txt)"
#endif

namespace lancer::sc {

// rt_grid's parameters as the Verilated model is built (-GRaysInFlight=...,
// -GCellQueue=...) and its record widths, under the RTL's names; the port
// types and the shell's parameters: rt_grid_unit, common/rt_trav_unit.h.
inline constexpr int RAYS_IN_FLIGHT = LANCER_GRID_RAYS_IN_FLIGHT;
inline constexpr int CELL_QUEUE = LANCER_GRID_CELL_QUEUE;  // CellQueue: cells per slot read and not finished
inline constexpr int GRID_RESOLUTION_W = fx::kGridResolutionBits;
inline constexpr int GRID_CELL_W = fx::kGridCellBits;

}  // namespace lancer::sc
