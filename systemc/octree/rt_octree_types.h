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

// rt_octree's parameters as the Verilated model is built (-GRaysInFlight=...)
// and the widths of its node records, under the RTL's names; the port types and
// the shell's parameters: rt_octree_unit, common/rt_trav_unit.h.
inline constexpr int RAYS_IN_FLIGHT = LANCER_OCTREE_RAYS_IN_FLIGHT;
inline constexpr int NODE_W = fx::kOctreeNodeBits;            // octree_node_t
inline constexpr int GROUP_W = NODE_W * fx::kOctreeChildren;  // octree_node_t [7:0]
inline constexpr int MAX_DEPTH = fx::kOctreeMaxDepth;         // P: stack entries
inline constexpr int ADV_LANES = 2;  // rt_octree_slots' AdvLanes: shared advance lanes besides the exit test's

}  // namespace lancer::sc::octree
