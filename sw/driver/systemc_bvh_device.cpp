#include "driver/systemc_traversal_device_impl.h"
#include "bvh/rt_bvh_unit.h"

LANCER_SYSTEMC_TRAVERSAL_UNIT(fx::BvhUnit, sc::rt_bvh_unit)
