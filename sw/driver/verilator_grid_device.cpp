#include "driver/verilator_grid_device.h"

#include "Vrt_grid.h"
#include "driver/verilator_traversal_run.h"

#ifndef LANCER_GRID_RAYS_IN_FLIGHT
#error "LANCER_GRID_RAYS_IN_FLIGHT must come from rt_grid_vlt (rtl/CMakeLists.txt)"
#endif

namespace lancer {

// rt_grid's members on the Verilated model; the rest is its descriptor.
template <>
struct VerilatedTraversalUnit<Vrt_grid> {
  using Desc = fx::GridUnit;
  static constexpr int kMaxSlots = LANCER_GRID_RAYS_IN_FLIGHT;
  static auto nodePort(Vrt_grid& t) {
    return std::tie(t.cell_req_valid_o, t.cell_req_addr_o, t.cell_req_tag_o, t.cell_req_ready_i, t.cell_rsp_valid_i,
                    t.cell_rsp_data_i, t.cell_rsp_tag_i);
  }
  static auto& configPort(Vrt_grid& t) { return t.cfg_res_i; }
};

template class VerilatorTraversalDevice<Vrt_grid, fx::GridImage>;

template <>
std::unique_ptr<GridDevice> makeVerilatorDevice<fx::GridUnit>() {
  return std::make_unique<VerilatorGridDevice>();
}

}  // namespace lancer
