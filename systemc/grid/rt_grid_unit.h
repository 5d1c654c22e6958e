#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "common/rt_trav_top.h"
#include "golden/grid.h"
#include "golden/records.h"
#include "grid/rt_grid_types.h"

namespace lancer::sc {

class rt_grid_model;

// rt_grid_unit: what the shared traversal-unit modules (common/rt_trav_unit.h)
// need to know of rt_grid: its cell port, its resolution port cfg_res_i, its
// records and its cycle model, which can hold the Verilated rt_isect.
struct rt_grid_unit : rt_trav_unit_types<RAYS_IN_FLIGHT, 3 * GRID_RESOLUTION_W, GRID_CELL_W, fx::kGridResFields,
                                          fx::kGridVisitFields> {
  static constexpr rt_trav_names kNames{.module = "rt_grid", .nodePort = "cell", .cfgPort = "cfg_res_i",
                                        .nodeRegion = "cell table", .unit = "grid",
                                        .slotsOption = "LANCER_GRID_RAYS_IN_FLIGHT",
                                        .rtlSources = "LANCER_RTL_GRID_SOURCES", .steps = "cells"};
  using image_t = fx::GridImage;
  using model_t = rt_grid_model;

  // cfg_res_i: {Rz, Ry, Rx}, Rx least significant.
  static cfg_t config(const image_t& image) {
    const fx::GridRes& r = image.res;
    return cfg_t(uint32_t(r[0]) | (uint32_t(r[1]) << GRID_RESOLUTION_W) | (uint32_t(r[2]) << (2 * GRID_RESOLUTION_W)));
  }

  // The cell port's responses: one cell table entry, packed when read.
  class node_packer {
   public:
    void start(const image_t& image) { image_ = &image; }
    size_t entries() const { return image_->cells.size(); }
    bool holds(uint32_t addr) const { return addr < entries(); }
    std::span<const uint32_t> wire(uint32_t addr) {
      const fx::GridCell& e = image_->cells[addr];
      const fx::u128 values[] = {e.first, e.count};
      wire_ = {};
      fx::packFields(fx::kGridCellFields, values, wire_);
      return wire_;
    }

   private:
    const image_t* image_ = nullptr;
    std::array<uint32_t, size_t(fx::wireWords(GRID_CELL_W))> wire_{};
  };

  // The DUT's cfg_res_i and cell port on the bench's signals.
  template <class Dut, class Bench>
  static void bindUnitPorts(Dut& dut, Bench& b) {
    dut.cfg_res_i(b.cfg_i);
    dut.cell_req_valid_o(b.node_req_valid_o);
    dut.cell_req_ready_i(b.node_req_ready_i);
    dut.cell_req_addr_o(b.node_req_addr_o);
    dut.cell_req_tag_o(b.node_req_tag_o);
    dut.cell_rsp_valid_i(b.node_rsp_valid_i);
    dut.cell_rsp_data_i(b.node_rsp_data_i);
    dut.cell_rsp_tag_i(b.node_rsp_tag_i);
  }
};

// rt_grid's SystemC system, testbench and memory (common/rt_trav_top.h).
using rt_grid_top = rt_trav_top<rt_grid_unit>;

}  // namespace lancer::sc
