#include "Vrt_octree.h"
#include "driver/verilator_traversal_run.h"

#ifndef LANCER_OCTREE_RAYS_IN_FLIGHT
#error "LANCER_OCTREE_RAYS_IN_FLIGHT must come from rt_octree_vlt (rtl/CMakeLists.txt)"
#endif

// rt_octree: the node port (a child group per read), the root's record on cfg_root_i.
LANCER_VERILATED_TRAVERSAL_UNIT(Vrt_octree, fx::OctreeUnit, LANCER_OCTREE_RAYS_IN_FLIGHT, cfg_root_i)
