#pragma once

// What the shared SystemC modules of a traversal unit (rt_trav_mem, rt_trav_tb,
// rt_trav_bench, rt_trav_top; systemc/common/) need to know of a unit: its
// traits class (grid/rt_grid_unit.h, octree/rt_octree_unit.h). Every traversal
// unit has the same ports (rtl/lib/'s traversal shell) except for
//   - the node/cell memory port: its name prefix (kNames.nodePort: "cell", "node")
//     and the record its responses carry (node_data_t: a grid cell, a child
//     group of 8 octree nodes), packed from the unit's image by a node_packer;
//   - one configuration port besides cfg_slots_i (kNames.cfgPort, cfg_t, config()):
//     rt_grid's cfg_res_i, rt_octree's cfg_root_i;
//   - the result and visit records (res_t, visit_t, kResFields, kVisitFields);
//   - the cycle model (model_t; one whose constructor takes an rt_isect_impl
//     can hold the Verilated rt_isect); the Verilated class is named in
//     systemc/rt_trav_units.cpp (rt_trav_rtl<Unit>), when the build has it.
// A unit's traits also bind the DUT's unit-specific ports (bindUnitPorts),
// since the DUT's C++ members carry the RTL's names.
//
// A unit traits class provides:
//   kNames                                     rt_trav_names (RTL module, port prefixes, messages)
//   rt_trav_unit_types<...> as a base          ray slots as the RTL is built, the port
//                                              types (cfg_slots_t, cfg_t, slot_t, mem_addr_t,
//                                              idx_data_t, node_data_t, res_t, visit_t), the
//                                              widths and field lists of the records
//   image_t                                    fx::GridImage, fx::OctreeImage
//   cfg_t config(const image_t&)               the configuration port's value of a run
//   node_packer                                start(image); holds(addr) and entries() for the
//                                              memory's address check; wire(addr): the response's
//                                              wire image
//   model_t                                    the cycle model
//   bindUnitPorts(dut, bench)                  cfg and node/cell ports of the DUT

#include <cstdint>
#include <string>

#include "golden/records.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

constexpr int clog2(uint64_t n) {
  int bits = 0;
  while ((uint64_t(1) << bits) < n) ++bits;
  return bits;
}

// A unit's names: its RTL module, the prefix of its node/cell port, its
// configuration port, the node table as memory errors name it, and for the
// driver's messages the unit, the build options of its slots and of its RTL
// sources, what its result record's element count counts.
struct rt_trav_names {
  const char* module;      // "rt_grid"
  const char* nodePort;    // "cell": cell_req_valid_o, ...
  const char* cfgPort;     // "cfg_res_i"
  const char* nodeRegion;  // "cell table"
  const char* unit;        // "grid"
  const char* slotsOption; // "LANCER_GRID_RAYS_IN_FLIGHT"
  const char* rtlSources;  // "LANCER_RTL_GRID_SOURCES"
  const char* steps;       // "cells"
};

// The traversal shell's parameters, every unit's (rtl/lib/; docs/octree-unit.md:
// as rt_grid's): the index buffer and its credits, the FIFO depths, the address width.
inline constexpr int IDX_BUF_DEPTH = 64;
inline constexpr int MEMREQ_FIFO_DEPTH = 2;
inline constexpr int VISIT_FIFO_DEPTH = 4;
inline constexpr int RES_FIFO_DEPTH = 2;
inline constexpr int MEM_ADDR_W = fx::kMemAddrBits;

// The port types of a unit from its parameters, under the names the traits
// provide (a unit's traits derive from it): RaysInFlight ray slots, a
// configuration port of CfgW bits, node/cell responses of NodeDataW bits, the
// result and visit records' field lists.
template <int RaysInFlight, int CfgW, int NodeDataW, const auto& ResFields, const auto& VisitFields>
struct rt_trav_unit_types {
  static_assert(RaysInFlight >= 1 && RaysInFlight <= 256, "RaysInFlight is 1..256");
  static constexpr int RAYS_IN_FLIGHT = RaysInFlight;
  static constexpr int SLOT_W = RaysInFlight > 1 ? clog2(RaysInFlight) : 1;
  static constexpr int NODE_DATA_W = NodeDataW;
  static constexpr int RESULT_W = fx::recordBits(ResFields);
  static constexpr int VISIT_W = fx::recordBits(VisitFields);
  static constexpr const auto& kResFields = ResFields;
  static constexpr const auto& kVisitFields = VisitFields;

  using cfg_slots_t = vl_port_t<clog2(RaysInFlight + 1)>;
  using cfg_t = vl_port_t<CfgW>;
  using slot_t = vl_port_t<SLOT_W>;
  using mem_addr_t = vl_port_t<MEM_ADDR_W>;
  using idx_data_t = vl_port_t<32>;
  using node_data_t = vl_port_t<NodeDataW>;
  using res_t = vl_port_t<RESULT_W>;
  using visit_t = vl_port_t<VISIT_W>;
};

// "<prefix>_<suffix>": the SystemC name of one port of a unit's node/cell
// memory port (rt_grid: cell_req_valid_o, rt_octree: node_req_valid_o), so
// that the shared modules' objects carry the RTL's names.
inline std::string portName(const char* prefix, const char* suffix) { return std::string(prefix) + "_" + suffix; }

// The Verilated SystemC class of a unit (Vrt_grid_sc, ...), or void when the
// build lacks it: specialized by systemc/rt_trav_units.cpp, the one file that
// includes the Verilated classes.
template <class Unit>
struct rt_trav_rtl {
  using type = void;
};

}  // namespace lancer::sc
