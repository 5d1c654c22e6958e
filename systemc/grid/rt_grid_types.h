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

// rt_grid's parameters as the Verilated model is built (-GRaysInFlight=..., -GCellQueue=...),
// and the derived widths under the RTL's names.
inline constexpr int RAYS_IN_FLIGHT = LANCER_GRID_RAYS_IN_FLIGHT;
inline constexpr int IDX_BUF_DEPTH = 64;
inline constexpr int CELL_QUEUE = LANCER_GRID_CELL_QUEUE;  // CellQueue: cells per slot read and not finished
inline constexpr int SLOT_W = RAYS_IN_FLIGHT > 1 ? clog2(RAYS_IN_FLIGHT) : 1;
inline constexpr int CFG_SLOTS_W = clog2(RAYS_IN_FLIGHT + 1);
inline constexpr int GRID_RESOLUTION_W = fx::kGridResolutionBits;
inline constexpr int MEM_ADDR_W = fx::kMemAddrBits;
inline constexpr int GRID_CELL_W = fx::kGridCellBits;
inline constexpr int GRID_VISIT_W = fx::kGridVisitBits;
inline constexpr int GRID_RESULT_W = fx::kGridResultBits;
// rt_grid's FIFO depths (rtl/grid/rt_grid.sv).
inline constexpr int MEMREQ_FIFO_DEPTH = 2;
inline constexpr int VISIT_FIFO_DEPTH = 4;
inline constexpr int RES_FIFO_DEPTH = 2;

using cfg_res_t = vl_port_t<3 * GRID_RESOLUTION_W>;
using cfg_slots_t = vl_port_t<CFG_SLOTS_W>;
using slot_t = vl_port_t<SLOT_W>;
using mem_addr_t = vl_port_t<MEM_ADDR_W>;
using grid_cell_t = vl_port_t<GRID_CELL_W>;
using grid_visit_t = vl_port_t<GRID_VISIT_W>;
using grid_res_t = vl_port_t<GRID_RESULT_W>;
using idx_data_t = vl_port_t<32>;

}  // namespace lancer::sc
