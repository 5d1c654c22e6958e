#include "Vrt_bvh.h"
#include "driver/verilator_traversal_run.h"

#ifndef LANCER_BVH_RAYS_IN_FLIGHT
#error "LANCER_BVH_RAYS_IN_FLIGHT must come from rt_bvh_vlt (rtl/CMakeLists.txt)"
#endif

// rt_bvh: the node port (one bvh_node_t, both children's boxes, per read), the root's reference on cfg_root_i.
LANCER_VERILATED_TRAVERSAL_UNIT(Vrt_bvh, fx::BvhUnit, LANCER_BVH_RAYS_IN_FLIGHT, cfg_root_i)
