#pragma once

// What the shared SystemC modules of a traversal unit (rt_trav_tb,
// rt_trav_bench, rt_trav_top, rt_trav_shell_model; systemc/common/) need to
// know of a unit: its traits class rt_<unit>_unit (<unit>/rt_<unit>_unit.h,
// generated from common/rt_trav_unit_traits.h.in), which derives from
// rt_trav_unit<RaysInFlight, Descriptor>. Everything but
// the cycle model and the DUT's own port names comes from the unit's
// descriptor (golden/unit.h): names, records, the configuration port's value,
// the node port's responses.
//
// A unit traits class provides:
//   rt_trav_unit<RaysInFlight, Descriptor> as a base: ray slots as the RTL is
//       built; kNames; image_t; the port types (cfg_slots_t, cfg_t, slot_t,
//       mem_addr_t, idx_data_t, node_data_t, res_t, visit_t), the widths and
//       field lists of the records; config(image), the configuration port's
//       value of a run; node_packer (start(image); holds(addr) and entries()
//       for the memory's address check; wire(addr): the response's wire image)
//   model_t                     the cycle model (one whose constructor takes
//                               an rt_isect_impl can hold the Verilated rt_isect);
//                               the Verilated class is named in
//                               systemc/<unit>/rt_<unit>_system.cpp (rt_trav_rtl<Unit>)
//   bindUnitPorts(dut, bench)   the DUT's configuration and node ports, by the
//                               RTL's names (its C++ members carry them; the
//                               configuration port's is the unit's
//                               unit_cfg_port, rtl/<unit>/unit.cmake)

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "golden/records.h"
#include "golden/unit.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

constexpr int clog2(uint64_t n) {
  int bits = 0;
  while ((uint64_t(1) << bits) < n) ++bits;
  return bits;
}

// The traversal shell's parameters, every unit's (rtl/lib/; docs/octree-unit.md:
// as rt_grid's): the index buffer and its credits, the FIFO depths, the address width.
inline constexpr int IDX_BUF_DEPTH = 64;
inline constexpr int MEMREQ_FIFO_DEPTH = 2;
inline constexpr int VISIT_FIFO_DEPTH = 4;
inline constexpr int RES_FIFO_DEPTH = 2;
inline constexpr int MEM_ADDR_W = fx::kMemAddrBits;

// The types and the memory-facing members of a unit, from its descriptor
// `Desc` and the ray slots it is built with.
template <int RaysInFlight, class Desc>
struct rt_trav_unit {
  static_assert(RaysInFlight >= 1 && RaysInFlight <= 256, "RaysInFlight is 1..256");
  static constexpr const fx::UnitNames& kNames = Desc::kNames;
  static constexpr int RAYS_IN_FLIGHT = RaysInFlight;
  static constexpr int SETUP_LATENCY = Desc::kSetupLatency;
  static constexpr int SLOT_W = RaysInFlight > 1 ? clog2(RaysInFlight) : 1;
  static constexpr int CFG_SLOTS_W = clog2(RaysInFlight + 1);
  static constexpr int NODE_W = fx::kNodeBitsOf<Desc>;
  static constexpr int NODE_DATA_W = NODE_W * int(Desc::kGroup);
  static constexpr int CFG_W = fx::kCfgBitsOf<Desc>;
  static constexpr int RESULT_W = fx::recordBits(Desc::kResFields);
  static constexpr int VISIT_W = fx::recordBits(Desc::kVisitFields);
  static constexpr auto kResFields = Desc::kResFields;
  static constexpr auto kVisitFields = Desc::kVisitFields;
  // A unit that can set a walk aside (the treelet schedule, docs/scheduling.md)
  // has a walk record: its suspension ports carry it (WALK_W bits; 1 otherwise, unused).
  static constexpr bool kSuspends = fx::SuspendsWalks<Desc>;
  static constexpr int WALK_W = kSuspends ? fx::kWalkBitsOf<Desc> : 1;
  static constexpr int BLOCK_SHIFT_W = [] {
    if constexpr (kSuspends) {
      return Desc::kBlockShiftBits;
    } else {
      return 1;
    }
  }();
  static_assert(Desc::kGroup == 1 || NODE_W % 32 == 0, "the nodes of a group start on word boundaries");

  using descriptor = Desc;
  using image_t = typename Desc::Image;
  using cfg_slots_t = vl_port_t<CFG_SLOTS_W>;
  using cfg_t = vl_port_t<CFG_W>;
  using slot_t = vl_port_t<SLOT_W>;
  using mem_addr_t = vl_port_t<MEM_ADDR_W>;
  using idx_data_t = vl_port_t<32>;
  using node_data_t = vl_port_t<NODE_DATA_W>;
  using res_t = vl_port_t<RESULT_W>;
  using visit_t = vl_port_t<VISIT_W>;

  // The configuration port's value of a run.
  static cfg_t config(const image_t& image) {
    std::array<uint32_t, size_t(fx::wireWords(CFG_W))> wire{};
    fx::packConfig<Desc>(image, wire);
    return toPort<CFG_W>(wire);
  }

  // The node port's responses: Desc::kGroup nodes from the address on. A
  // single node is packed when read; a group (read many times) on first use.
  class node_packer {
    static constexpr size_t kNodeWords = size_t(fx::wireWords(NODE_W));
    static constexpr size_t kGroupWords = Desc::kGroup * kNodeWords;

   public:
    void start(const image_t& image) {
      image_ = &image;
      if constexpr (Desc::kGroup > 1) {
        packed_.assign(entries(), 0);
        wire_.assign(entries() * kGroupWords, 0);
      }
    }
    size_t entries() const { return Desc::nodes(*image_).size(); }
    bool holds(uint32_t addr) const { return uint64_t(addr) + Desc::kGroup <= entries(); }
    std::span<const uint32_t> wire(uint32_t addr) {
      const auto& nodes = Desc::nodes(*image_);
      if constexpr (Desc::kGroup == 1) {
        one_ = {};
        fx::packNode<Desc>(nodes[addr], one_);
        return one_;
      } else {
        const std::span<uint32_t> w(wire_.data() + size_t(addr) * kGroupWords, kGroupWords);
        if (!packed_[addr]) {
          for (size_t i = 0; i < Desc::kGroup; ++i) fx::packNode<Desc>(nodes[addr + i], w.subspan(i * kNodeWords, kNodeWords));
          packed_[addr] = 1;
        }
        return w;
      }
    }

   private:
    const image_t* image_ = nullptr;
    std::array<uint32_t, kNodeWords> one_{};
    std::vector<uint32_t> wire_;
    std::vector<uint8_t> packed_;
  };
};

// The Verilated SystemC class of a unit (Vrt_grid_sc, ...), or void when the
// build lacks it: specialized by the unit's rt_<unit>_system.cpp (generated from
// common/rt_trav_system.cpp.in), the one file that includes its Verilated class.
template <class Unit>
struct rt_trav_rtl {
  using type = void;
};

}  // namespace lancer::sc
