#include "driver/systemc_traversal_device_impl.h"
#include "grid/rt_grid_unit.h"

LANCER_SYSTEMC_TRAVERSAL_UNIT(fx::GridUnit, sc::rt_grid_unit)
