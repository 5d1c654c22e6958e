#include "driver/verilator_octree_device.h"

#include "Vrt_octree.h"
#include "driver/verilator_traversal_run.h"

#ifndef LANCER_OCTREE_RAYS_IN_FLIGHT
#error "LANCER_OCTREE_RAYS_IN_FLIGHT must come from rt_octree_vlt (rtl/CMakeLists.txt)"
#endif

namespace lancer {

// rt_octree's members on the Verilated model; the rest is its descriptor.
template <>
struct VerilatedTraversalUnit<Vrt_octree> {
  using Desc = fx::OctreeUnit;
  static constexpr int kMaxSlots = LANCER_OCTREE_RAYS_IN_FLIGHT;
  static auto nodePort(Vrt_octree& t) {
    return std::tie(t.node_req_valid_o, t.node_req_addr_o, t.node_req_tag_o, t.node_req_ready_i, t.node_rsp_valid_i,
                    t.node_rsp_data_i, t.node_rsp_tag_i);
  }
  static auto& configPort(Vrt_octree& t) { return t.cfg_root_i; }
};

template class VerilatorTraversalDevice<Vrt_octree, fx::OctreeImage>;

template <>
std::unique_ptr<OctreeDevice> makeVerilatorDevice<fx::OctreeUnit>() {
  return std::make_unique<VerilatorOctreeDevice>();
}

}  // namespace lancer
