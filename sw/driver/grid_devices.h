#pragma once

// The grid unit's SystemC and Verilated devices by their types, for tests that
// need more than the model table's TraversalDevice (port traces, the mixed model).

#include "driver/systemc_traversal_device.h"
#include "driver/verilator_traversal_device.h"

class Vrt_grid;
namespace lancer::sc {
struct rt_grid_unit;
}

namespace lancer {

// "systemc" (rt_grid_model), "rtl-systemc" (Vrt_grid_sc) and the mixed
// Impl::ModelRtlIsect (rt_grid_model with the Verilated rt_isect inside).
using SystemCGridDevice = SystemCTraversalDevice<fx::GridImage, sc::rt_grid_unit>;

// rt_grid (rtl/grid/rt_grid.sv, with its rt_isect). Node reads may run up to
// CellQueue - 1 cells past a ray's last cell (prefetch).
using VerilatorGridDevice = VerilatorTraversalDevice<Vrt_grid, fx::GridImage>;

}  // namespace lancer
