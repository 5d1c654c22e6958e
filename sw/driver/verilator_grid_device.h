#pragma once

#include "driver/verilator_traversal_device.h"

class Vrt_grid;

namespace lancer {

extern template class VerilatorTraversalDevice<Vrt_grid, fx::GridImage>;

// rt_grid (rtl/grid/rt_grid.sv, with its rt_isect) behind GridDevice. A node
// response is one grid cell; the run's configuration is the resolution
// (cfg_res_i), checked against 1..fx::kGridResMax per axis (InputError). Node
// reads may run up to CellQueue - 1 cells past a ray's last cell (prefetch).
// Its traits are in verilator_grid_device.cpp.
class VerilatorGridDevice final : public VerilatorTraversalDevice<Vrt_grid, fx::GridImage> {};

}  // namespace lancer
