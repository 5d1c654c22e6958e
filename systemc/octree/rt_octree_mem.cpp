#include "octree/rt_octree_mem.h"

#include <array>
#include <stdexcept>

#include <fmt/format.h>

#include "common/rt_record_bits.h"

namespace lancer::sc {

using namespace octree;

rt_octree_mem::rt_octree_mem(sc_core::sc_module_name name)
    : sc_core::sc_module(name),
      clk_i("clk_i"),
      node_req_valid_o("node_req_valid_o"),
      node_req_ready_i("node_req_ready_i"),
      node_req_addr_o("node_req_addr_o"),
      node_req_tag_o("node_req_tag_o"),
      node_rsp_valid_i("node_rsp_valid_i"),
      node_rsp_data_i("node_rsp_data_i"),
      node_rsp_tag_i("node_rsp_tag_i"),
      idx_req_valid_o("idx_req_valid_o"),
      idx_req_ready_i("idx_req_ready_i"),
      idx_req_addr_o("idx_req_addr_o"),
      idx_req_tag_o("idx_req_tag_o"),
      idx_rsp_valid_i("idx_rsp_valid_i"),
      idx_rsp_data_i("idx_rsp_data_i"),
      idx_rsp_tag_i("idx_rsp_tag_i"),
      tri_req_valid_o("tri_req_valid_o"),
      tri_req_ready_i("tri_req_ready_i"),
      tri_req_addr_o("tri_req_addr_o"),
      tri_req_tag_o("tri_req_tag_o"),
      tri_rsp_valid_i("tri_rsp_valid_i"),
      tri_rsp_data_i("tri_rsp_data_i"),
      tri_rsp_tag_i("tri_rsp_tag_i") {
  SC_METHOD(edge);
  sensitive << clk_i.pos();
  dont_initialize();
}

void rt_octree_mem::start(const fx::OctreeImage& image, int latency, int jitter, uint64_t seed) {
  image_ = &image;
  groupPacked_.assign(image.nodes.size(), 0);
  groupWire_.resize(image.nodes.size() * fx::kOctreeGroupWords);
  triPacked_.assign(image.triangles.size(), 0);
  triWire_.resize(image.triangles.size() * fx::kIsectTriWords);
  node_.restart(latency, jitter, seed * 3 + 1);
  idx_.restart(latency, jitter, seed * 3 + 2);
  tri_.restart(latency, jitter, seed * 3 + 3);
  cycle_ = 0;
}

void rt_octree_mem::edge() {
  if (!readyWritten_) {
    node_req_ready_i.write(true);
    idx_req_ready_i.write(true);
    tri_req_ready_i.write(true);
    readyWritten_ = true;
  }
  if (image_ == nullptr) {
    node_rsp_valid_i.write(false);
    idx_rsp_valid_i.write(false);
    tri_rsp_valid_i.write(false);
    return;
  }
  // The requests of the cycle that ends at this edge, then the responses of the next.
  const uint64_t c = cycle_++;
  if (node_req_valid_o.read()) node_.request(c, uint32_t(node_req_addr_o.read()), uint32_t(node_req_tag_o.read()));
  if (idx_req_valid_o.read()) idx_.request(c, uint32_t(idx_req_addr_o.read()), uint32_t(idx_req_tag_o.read()));
  if (tri_req_valid_o.read()) tri_.request(c, uint32_t(tri_req_addr_o.read()), uint32_t(tri_req_tag_o.read()));

  auto outside = [this](const char* region, uint32_t addr, size_t size) {
    const std::string what = fmt::format("{} read at {} outside the image ({} entries)", region, addr, size);
    SC_REPORT_ERROR(name(), what.c_str());
    throw std::out_of_range(what);  // not reached when errors throw (sw/driver/systemc_kernel.cpp)
  };
  uint32_t addr = 0, tag = 0;
  const bool node = node_.respond(c + 1, addr, tag);
  node_rsp_valid_i.write(node);
  if (node) {
    if (uint64_t(addr) + fx::kOctreeChildren > image_->nodes.size()) {
      outside("node table (child group)", addr, image_->nodes.size());
    }
    const std::span<uint32_t> wire(groupWire_.data() + size_t(addr) * fx::kOctreeGroupWords, fx::kOctreeGroupWords);
    if (!groupPacked_[addr]) {
      fx::packChildGroup(*image_, addr, wire);
      groupPacked_[addr] = 1;
    }
    assignPort<GROUP_W>(groupPort_, wire);
    node_rsp_data_i.write(groupPort_);
    node_rsp_tag_i.write(slot_t(tag));
  }
  const bool idx = idx_.respond(c + 1, addr, tag);
  idx_rsp_valid_i.write(idx);
  if (idx) {
    if (addr >= image_->indices.size()) outside("index list", addr, image_->indices.size());
    idx_rsp_data_i.write(idx_data_t(image_->indices[addr]));
    idx_rsp_tag_i.write(slot_t(tag));
  }
  const bool tri = tri_.respond(c + 1, addr, tag);
  tri_rsp_valid_i.write(tri);
  if (tri) {
    if (addr >= image_->triangles.size()) outside("triangle table", addr, image_->triangles.size());
    const std::span<uint32_t> wire(triWire_.data() + size_t(addr) * fx::kIsectTriWords, fx::kIsectTriWords);
    if (!triPacked_[addr]) {
      fx::packWire(image_->triangles[addr], wire);
      triPacked_[addr] = 1;
    }
    assignPort<ISECT_TRI_W>(triPort_, wire);
    tri_rsp_data_i.write(triPort_);
    tri_rsp_tag_i.write(slot_t(tag));
  }
}

}  // namespace lancer::sc
