#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <systemc>

#include "common/rt_record_bits.h"
#include "common/rt_trav_ports.h"
#include "common/rt_trav_unit.h"
#include "golden/stimulus.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// rt_trav_mem: the memory behind a traversal unit's three read ports, serving
// one image of the unit (Unit: a traits class, common/rt_trav_unit.h): the
// node/cell port returns Unit::node_packer's record at the requested address
// (a grid cell; an octree child group, nodes addr .. addr+7), the index and
// triangle ports one index-list entry and one triangle. Behavioural model of
// a memory system, but clocked: SC_METHOD on clk_i.posedge samples the
// requests of the cycle that ends (req_ready is always 1) and drives the
// responses of the next one, each port timed by an fx::MemoryReadPort
// (latency, jitter, in order, one response per cycle) seeded seed*3+1, +2, +3
// for the node, index and triangle ports, as the C++ Verilated devices, so
// that for the same TraversalRunOptions all of them answer in the same cycles.
// Ports carry the names of the unit's ports they connect to (node_*: the
// unit's kNames.nodePort prefix, cell_* for rt_grid). An address outside the image
// is an SC_REPORT_ERROR (the device throws).
template <class Unit>
class rt_trav_mem : public sc_core::sc_module,
                    public rt_trav_node_port<Unit, sc_core::sc_out, sc_core::sc_in>,
                    public rt_trav_mem_ports<Unit, sc_core::sc_out, sc_core::sc_in> {
 public:
  sc_core::sc_in<bool> clk_i{"clk_i"};

  SC_HAS_PROCESS(rt_trav_mem);
  explicit rt_trav_mem(sc_core::sc_module_name name) : sc_core::sc_module(name) {
    SC_METHOD(edge);
    sensitive << clk_i.pos();
    dont_initialize();
  }

  // Arms the memory for one run (call while the simulation is paused): empties
  // the ports and reseeds them. The image must outlive the run.
  void start(const typename Unit::image_t& image, int latency, int jitter, uint64_t seed) {
    image_ = &image;
    nodes_.start(image);
    triPacked_.assign(image.triangles.size(), 0);
    triWire_.resize(image.triangles.size() * fx::kIsectTriWords);
    node_.restart(latency, jitter, seed * 3 + 1);
    idx_.restart(latency, jitter, seed * 3 + 2);
    tri_.restart(latency, jitter, seed * 3 + 3);
    cycle_ = 0;
  }
  // Stops serving (no responses, requests ignored) until the next start().
  void stop() { image_ = nullptr; }

 private:
  void edge() {
    if (!readyWritten_) {
      this->node_req_ready_i.write(true);
      this->idx_req_ready_i.write(true);
      this->tri_req_ready_i.write(true);
      readyWritten_ = true;
    }
    if (image_ == nullptr) {
      this->node_rsp_valid_i.write(false);
      this->idx_rsp_valid_i.write(false);
      this->tri_rsp_valid_i.write(false);
      return;
    }
    // The requests of the cycle that ends at this edge, then the responses of the next.
    const uint64_t c = cycle_++;
    if (this->node_req_valid_o.read()) node_.request(c, uint32_t(this->node_req_addr_o.read()), uint32_t(this->node_req_tag_o.read()));
    if (this->idx_req_valid_o.read()) idx_.request(c, uint32_t(this->idx_req_addr_o.read()), uint32_t(this->idx_req_tag_o.read()));
    if (this->tri_req_valid_o.read()) tri_.request(c, uint32_t(this->tri_req_addr_o.read()), uint32_t(this->tri_req_tag_o.read()));

    uint32_t addr = 0, tag = 0;
    const bool node = node_.respond(c + 1, addr, tag);
    this->node_rsp_valid_i.write(node);
    if (node) {
      if (!nodes_.holds(addr)) outside(Unit::kNames.nodeTable, addr, nodes_.entries());
      assignPort<Unit::NODE_DATA_W>(nodePort_, nodes_.wire(addr));
      this->node_rsp_data_i.write(nodePort_);
      this->node_rsp_tag_i.write(typename Unit::slot_t(tag));
    }
    const bool idx = idx_.respond(c + 1, addr, tag);
    this->idx_rsp_valid_i.write(idx);
    if (idx) {
      if (addr >= image_->indices.size()) outside("index list", addr, image_->indices.size());
      this->idx_rsp_data_i.write(typename Unit::idx_data_t(image_->indices[addr]));
      this->idx_rsp_tag_i.write(typename Unit::slot_t(tag));
    }
    const bool tri = tri_.respond(c + 1, addr, tag);
    this->tri_rsp_valid_i.write(tri);
    if (tri) {
      if (addr >= image_->triangles.size()) outside("triangle table", addr, image_->triangles.size());
      const std::span<uint32_t> wire(triWire_.data() + size_t(addr) * fx::kIsectTriWords, fx::kIsectTriWords);
      if (!triPacked_[addr]) {
        fx::packWire(image_->triangles[addr], wire);
        triPacked_[addr] = 1;
      }
      assignPort<ISECT_TRI_W>(triPort_, wire);
      this->tri_rsp_data_i.write(triPort_);
      this->tri_rsp_tag_i.write(typename Unit::slot_t(tag));
    }
  }

  void outside(const char* region, uint32_t addr, size_t size) {
    const std::string what = fmt::format("{} read at {} outside the image ({} entries)", region, addr, size);
    SC_REPORT_ERROR(name(), what.c_str());
    throw std::out_of_range(what);  // not reached when errors throw (sw/driver/systemc_kernel.cpp)
  }

  const typename Unit::image_t* image_ = nullptr;
  fx::MemoryReadPort node_, idx_, tri_;  // timing: sw/golden/stimulus.h
  uint64_t cycle_ = 0;
  bool readyWritten_ = false;  // req_ready is constant 1
  typename Unit::node_packer nodes_;
  // Triangle wire images packed on first use in a run (fx::packWire by triangle id).
  std::vector<uint32_t> triWire_;
  std::vector<uint8_t> triPacked_;
  // The response ports' values, reused (an sc_bv allocates when constructed).
  typename Unit::node_data_t nodePort_{};
  isect_tri_t triPort_{};
};

}  // namespace lancer::sc
