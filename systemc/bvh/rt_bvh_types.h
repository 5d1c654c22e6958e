#pragma once

// The port types of rt_bvh as SystemC sees them, shared by the hand-written
// cycle model (rt_bvh_model), the Verilated RTL (Vrt_bvh_sc), the memory model
// and the testbench (common/rt_trav_unit.h derives them from the descriptor).
// In their own namespace: the other units use the same RTL names with other values.

#include <cstdint>

#include "common/rt_trav_unit.h"
#include "golden/bvh_formats.h"

#ifndef LANCER_BVH_RAYS_IN_FLIGHT
#error "LANCER_BVH_RAYS_IN_FLIGHT must come from the build (systemc/CMakeLists.txt)"
#endif

namespace lancer::sc::bvh {

// rt_bvh's parameters as the Verilated model is built (-GRaysInFlight=...) and
// its formats under the RTL's names.
inline constexpr int RAYS_IN_FLIGHT = LANCER_BVH_RAYS_IN_FLIGHT;
inline constexpr int NODE_W = fx::kBvhNodeBits;            // bvh_node_t
inline constexpr int STACK_DEPTH = fx::kBvhStackDepth;     // entries per slot
inline constexpr int BOX_LATENCY = fx::kBvhBoxLatency;     // rt_bvh_box's stages

}  // namespace lancer::sc::bvh
