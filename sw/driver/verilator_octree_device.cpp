#include "driver/verilator_octree_device.h"

#include <fmt/format.h>

#include "Vrt_octree.h"
#include "common/error.h"
#include "driver/verilator_traversal_run.h"

#ifndef LANCER_OCTREE_RAYS_IN_FLIGHT
#error "LANCER_OCTREE_RAYS_IN_FLIGHT must come from rt_octree_vlt (rtl/CMakeLists.txt)"
#endif

namespace lancer {

// rt_octree's side of the Verilated traversal device: a node response is the
// child group first .. first+7; the configuration is the root's record.
template <>
struct VerilatedTraversalUnit<Vrt_octree> {
  static constexpr VerilatedTraversalNames kNames{"rt_octree", "octree", "LANCER_OCTREE_RAYS_IN_FLIGHT",
                                                  "nodes", "child group", "node table"};
  static constexpr int kMaxSlots = LANCER_OCTREE_RAYS_IN_FLIGHT;
  static constexpr std::span<const fx::FieldSpec> kVisitFields = fx::kOctreeVisitFields;
  static constexpr std::span<const fx::FieldSpec> kResFields = fx::kOctreeResFields;
  static constexpr size_t kGroup = fx::kOctreeChildren;

  static const std::vector<fx::OctreeNode>& nodes(const fx::OctreeImage& image) { return image.nodes; }
  // octree_node_t as the 64-bit integer of its wire image (fx::packFields).
  static uint64_t packNode(const fx::OctreeNode& node) {
    static_assert(fx::kOctreeNodeBits == 64, "octree_node_t is one 64-bit word");
    const fx::u128 values[] = {node.leaf ? 1u : 0u, node.count, node.first};
    std::array<uint32_t, 2> wire{};
    fx::packFields(fx::kOctreeNodeFields, values, wire);
    return uint64_t(wire[0]) | (uint64_t(wire[1]) << 32);
  }
  static auto nodePort(Vrt_octree& t) {
    return std::tie(t.node_req_valid_o, t.node_req_addr_o, t.node_req_tag_o, t.node_req_ready_i, t.node_rsp_valid_i,
                    t.node_rsp_data_i, t.node_rsp_tag_i);
  }
  static void checkImage(const fx::OctreeImage& image, std::span<const fx::QRay> rays) {
    if (image.nodes.empty()) throw InputError("the octree image has no nodes (node 0 is the root)");
    for (const fx::QRay& ray : rays) {
      if (ray.dir[0] == 0 && ray.dir[1] == 0 && ray.dir[2] == 0) {
        throw InputError(
            fmt::format("ray {} has a zero direction: the octree unit needs a non-zero component", ray.id));
      }
    }
  }
  static void idleConfig(Vrt_octree& top) { top.cfg_root_i = 0; }
  static void configure(Vrt_octree& top, const fx::OctreeImage& image) { top.cfg_root_i = packNode(image.nodes[0]); }
};

template class VerilatorTraversalDevice<Vrt_octree, fx::OctreeImage>;

}  // namespace lancer
