#include "driver/verilator_grid_device.h"

#include <fmt/format.h>

#include "Vrt_grid.h"
#include "common/error.h"
#include "driver/verilator_traversal_run.h"

#ifndef LANCER_GRID_RAYS_IN_FLIGHT
#error "LANCER_GRID_RAYS_IN_FLIGHT must come from rt_grid_vlt (rtl/CMakeLists.txt)"
#endif

namespace lancer {

// rt_grid's side of the Verilated traversal device: a node response is one
// cell, {first, count}; the configuration is the resolution.
template <>
struct VerilatedTraversalUnit<Vrt_grid> {
  static constexpr VerilatedTraversalNames kNames{"rt_grid", "grid", "LANCER_GRID_RAYS_IN_FLIGHT",
                                                  "cells", "cell", "cell table"};
  static constexpr int kMaxSlots = LANCER_GRID_RAYS_IN_FLIGHT;
  static constexpr std::span<const fx::FieldSpec> kVisitFields = fx::kGridVisitFields;
  static constexpr std::span<const fx::FieldSpec> kResFields = fx::kGridResFields;
  static constexpr size_t kGroup = 1;

  static const std::vector<fx::GridCell>& nodes(const fx::GridImage& image) { return image.cells; }
  static uint64_t packNode(const fx::GridCell& c) {
    static_assert(fx::kGridCellBits == 64 && fx::kGridCellFields[1].width == 32);  // {first, count}
    return (uint64_t(c.first) << trav_detail::fieldLsb(fx::kGridCellFields, 0)) |
           (uint64_t(c.count) << trav_detail::fieldLsb(fx::kGridCellFields, 1));
  }
  static auto nodePort(Vrt_grid& t) {
    return std::tie(t.cell_req_valid_o, t.cell_req_addr_o, t.cell_req_tag_o, t.cell_req_ready_i, t.cell_rsp_valid_i,
                    t.cell_rsp_data_i, t.cell_rsp_tag_i);
  }
  static void checkImage(const fx::GridImage& image, std::span<const fx::QRay>) {
    for (int a = 0; a < 3; ++a) {
      if (image.res[a] < 1 || image.res[a] > fx::kGridResMax) {
        throw InputError(fmt::format("grid resolution {} on axis {} is out of range 1..{}", image.res[a], a,
                                     fx::kGridResMax));
      }
    }
  }
  static uint32_t packRes(uint32_t x, uint32_t y, uint32_t z) { return x | (y << 9) | (z << 18); }
  static void idleConfig(Vrt_grid& top) { top.cfg_res_i = packRes(1, 1, 1); }
  static void configure(Vrt_grid& top, const fx::GridImage& image) {
    top.cfg_res_i = packRes(uint32_t(image.res[0]), uint32_t(image.res[1]), uint32_t(image.res[2]));
  }
};

template class VerilatorTraversalDevice<Vrt_grid, fx::GridImage>;

}  // namespace lancer
