#include "Vrt_grid.h"
#include "driver/verilator_traversal_run.h"

#ifndef LANCER_GRID_RAYS_IN_FLIGHT
#error "LANCER_GRID_RAYS_IN_FLIGHT must come from rt_grid_vlt (rtl/CMakeLists.txt)"
#endif

// rt_grid: the cell port, the resolution on cfg_res_i.
LANCER_VERILATED_TRAVERSAL_UNIT(Vrt_grid, fx::GridUnit, LANCER_GRID_RAYS_IN_FLIGHT, cfg_res_i)
