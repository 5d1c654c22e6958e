#include "driver/systemc_traversal_device_impl.h"
#include "octree/rt_octree_unit.h"

LANCER_SYSTEMC_TRAVERSAL_UNIT(fx::OctreeUnit, sc::rt_octree_unit)
