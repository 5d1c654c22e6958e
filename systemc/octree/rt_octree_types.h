#pragma once

// The port types of rt_octree as SystemC sees them, shared by the hand-written
// cycle model (rt_octree_model), the Verilated RTL (Vrt_octree_sc), the memory
// model and the testbench, so that either implementation drops into the same
// sockets. Widths from rt_pkg's generator (sw/golden/records.h, formats.h);
// Verilator's type mapping as in isect/rt_isect_types.h (vl_port_t<W>: bool,
// uint32_t, uint64_t, sc_bv<W>). In their own namespace: rt_grid's types use
// the same RTL names (RAYS_IN_FLIGHT, SLOT_W, ...) with other values.

#include <cstdint>

#include "golden/formats.h"
#include "common/rt_trav_unit.h"
#include "golden/records.h"
#include "isect/rt_isect_types.h"

#ifndef LANCER_OCTREE_RAYS_IN_FLIGHT
#error "LANCER_OCTREE_RAYS_IN_FLIGHT must come from the build (systemc/CMakeLists.txt)"
#endif

namespace lancer::sc::octree {

// rt_octree's parameters as the Verilated model is built (-GRaysInFlight=...),
// and the derived widths under the RTL's names.
inline constexpr int RAYS_IN_FLIGHT = LANCER_OCTREE_RAYS_IN_FLIGHT;
static_assert(RAYS_IN_FLIGHT >= 1 && RAYS_IN_FLIGHT <= 256, "RaysInFlight is 1..256");
inline constexpr int IDX_BUF_DEPTH = 64;
inline constexpr int SLOT_W = RAYS_IN_FLIGHT > 1 ? clog2(RAYS_IN_FLIGHT) : 1;
inline constexpr int CFG_SLOTS_W = clog2(RAYS_IN_FLIGHT + 1);
inline constexpr int MEM_ADDR_W = fx::kMemAddrBits;
inline constexpr int NODE_W = fx::kOctreeNodeBits;                  // octree_node_t
inline constexpr int GROUP_W = NODE_W * fx::kOctreeChildren;        // octree_node_t [7:0]
inline constexpr int VISIT_W = fx::kOctreeVisitBits;                // octree_visit_t
inline constexpr int RESULT_W = fx::kOctreeResultBits;              // octree_res_t
inline constexpr int MAX_DEPTH = fx::kOctreeMaxDepth;               // P: stack entries
// rt_octree's FIFO depths (docs/octree-unit.md: as rt_grid's).
inline constexpr int MEMREQ_FIFO_DEPTH = 2;
inline constexpr int VISIT_FIFO_DEPTH = 4;
inline constexpr int RES_FIFO_DEPTH = 2;
// rt_octree_slots' AdvLanes: shared advance lanes besides the exit test's.
inline constexpr int ADV_LANES = 2;

using cfg_slots_t = vl_port_t<CFG_SLOTS_W>;
using slot_t = vl_port_t<SLOT_W>;
using mem_addr_t = vl_port_t<MEM_ADDR_W>;
using node_t = vl_port_t<NODE_W>;
using group_t = vl_port_t<GROUP_W>;
using visit_t = vl_port_t<VISIT_W>;
using res_t = vl_port_t<RESULT_W>;
using idx_data_t = vl_port_t<32>;

}  // namespace lancer::sc::octree
