#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "common/rt_trav_top.h"
#include "golden/octree.h"
#include "golden/records.h"
#include "octree/rt_octree_types.h"

namespace lancer::sc {

class rt_octree_model;

// rt_octree_unit: what the shared traversal-unit modules (common/rt_trav_unit.h)
// need to know of rt_octree: its node port (a child group of 8 nodes per
// response), its root port cfg_root_i, its records and its cycle model.
struct rt_octree_unit : rt_trav_unit_types<octree::RAYS_IN_FLIGHT, octree::NODE_W, octree::GROUP_W,
                                            fx::kOctreeResFields, fx::kOctreeVisitFields> {
  static constexpr rt_trav_names kNames{.module = "rt_octree", .nodePort = "node", .cfgPort = "cfg_root_i",
                                        .nodeRegion = "node table (child group)", .unit = "octree",
                                        .slotsOption = "LANCER_OCTREE_RAYS_IN_FLIGHT",
                                        .rtlSources = "LANCER_RTL_OCTREE_SOURCES", .steps = "nodes"};
  using image_t = fx::OctreeImage;
  using model_t = rt_octree_model;

  // cfg_root_i: the image's node 0 as an octree_node_t.
  static cfg_t config(const image_t& image) {
    std::array<uint32_t, size_t(fx::wireWords(octree::NODE_W))> root{};
    const fx::OctreeNode& r = image.nodes.at(0);
    const fx::u128 values[] = {r.leaf ? 1u : 0u, r.count, r.first};
    fx::packFields(fx::kOctreeNodeFields, values, root);
    return toPort<octree::NODE_W>(root);
  }

  // The node port's responses: the child group at addr (fx::packChildGroup:
  // nodes addr .. addr+7 as octree_node_t [7:0]), packed on first use in a run
  // (a group is read many times).
  class node_packer {
   public:
    void start(const image_t& image) {
      image_ = &image;
      packed_.assign(image.nodes.size(), 0);
      wire_.resize(image.nodes.size() * fx::kOctreeGroupWords);
    }
    size_t entries() const { return image_->nodes.size(); }
    bool holds(uint32_t addr) const { return uint64_t(addr) + fx::kOctreeChildren <= entries(); }
    std::span<const uint32_t> wire(uint32_t addr) {
      const std::span<uint32_t> w(wire_.data() + size_t(addr) * fx::kOctreeGroupWords, fx::kOctreeGroupWords);
      if (!packed_[addr]) {
        fx::packChildGroup(*image_, addr, w);
        packed_[addr] = 1;
      }
      return w;
    }

   private:
    const image_t* image_ = nullptr;
    std::vector<uint32_t> wire_;
    std::vector<uint8_t> packed_;
  };

  // The DUT's cfg_root_i and node port on the bench's signals.
  template <class Dut, class Bench>
  static void bindUnitPorts(Dut& dut, Bench& b) {
    dut.cfg_root_i(b.cfg_i);
    b.bindNodePort(dut);
  }
};

// rt_octree's SystemC system, testbench and memory (common/rt_trav_top.h).
using rt_octree_top = rt_trav_top<rt_octree_unit>;

}  // namespace lancer::sc
