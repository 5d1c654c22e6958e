#pragma once

#include "driver/systemc_traversal_device.h"

namespace lancer {

namespace sc {
struct rt_grid_unit;
}  // namespace sc

// The grid unit in SystemC (systemc/grid/, sw/driver/systemc_traversal_device.h):
// "systemc" (rt_grid_model), "rtl-systemc" (Vrt_grid_sc) and the mixed
// Impl::ModelRtlIsect (rt_grid_model with the Verilated rt_isect inside).
using SystemCGridDevice = SystemCTraversalDevice<fx::GridImage, sc::rt_grid_unit>;

}  // namespace lancer
