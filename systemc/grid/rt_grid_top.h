#pragma once

#include "common/rt_trav_top.h"
#include "grid/rt_grid_unit.h"

namespace lancer::sc {

// rt_grid's SystemC system (common/rt_trav_top.h): the cycle model rt_grid_model
// with rt_isect_model inside, the same with the Verilated rt_isect inside
// (mixed: rt_trav_impl::model_rtl_isect), and Vrt_grid_sc (rtl/grid/rt_grid.sv
// with its rt_isect, Verilated with --sc), each on its bench.
using rt_grid_top = rt_trav_top<rt_grid_unit>;
using rt_grid_impl = rt_trav_impl;
using rt_grid_tb = rt_trav_tb<rt_grid_unit>;
using rt_grid_mem = rt_trav_mem<rt_grid_unit>;

}  // namespace lancer::sc
