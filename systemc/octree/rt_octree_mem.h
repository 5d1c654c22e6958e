#pragma once

#include <cstdint>
#include <vector>

#include <systemc>

#include "golden/octree.h"
#include "golden/stimulus.h"
#include "octree/rt_octree_types.h"

namespace lancer::sc {

// rt_octree_mem: the memory behind rt_octree's three read ports, serving one
// fx::OctreeImage: the node port returns the child group at the requested
// node (fx::packChildGroup: nodes addr .. addr+7 as octree_node_t [7:0]), the
// index and triangle ports one index-list entry and one triangle. Behavioural
// but clocked: SC_METHOD on clk_i.posedge samples the requests of the cycle
// that ends (req_ready is always 1) and drives the responses of the next one,
// each port timed by an fx::MemoryReadPort (latency, jitter, in order, one
// response per cycle) seeded seed*3+1, +2, +3 for the node, index and triangle
// ports, as every traversal-unit memory (rt_grid_mem, the C++ Verilated
// devices), so that for the same TraversalRunOptions all of them answer in the
// same cycles. Ports carry the names of the rt_octree ports they connect to.
// An address outside the image is an SC_REPORT_ERROR (the device throws).
SC_MODULE(rt_octree_mem) {
  sc_core::sc_in<bool> clk_i;

  sc_core::sc_in<bool> node_req_valid_o;
  sc_core::sc_out<bool> node_req_ready_i;
  sc_core::sc_in<octree::mem_addr_t> node_req_addr_o;
  sc_core::sc_in<octree::slot_t> node_req_tag_o;
  sc_core::sc_out<bool> node_rsp_valid_i;
  sc_core::sc_out<octree::group_t> node_rsp_data_i;
  sc_core::sc_out<octree::slot_t> node_rsp_tag_i;

  sc_core::sc_in<bool> idx_req_valid_o;
  sc_core::sc_out<bool> idx_req_ready_i;
  sc_core::sc_in<octree::mem_addr_t> idx_req_addr_o;
  sc_core::sc_in<octree::slot_t> idx_req_tag_o;
  sc_core::sc_out<bool> idx_rsp_valid_i;
  sc_core::sc_out<octree::idx_data_t> idx_rsp_data_i;
  sc_core::sc_out<octree::slot_t> idx_rsp_tag_i;

  sc_core::sc_in<bool> tri_req_valid_o;
  sc_core::sc_out<bool> tri_req_ready_i;
  sc_core::sc_in<octree::mem_addr_t> tri_req_addr_o;
  sc_core::sc_in<octree::slot_t> tri_req_tag_o;
  sc_core::sc_out<bool> tri_rsp_valid_i;
  sc_core::sc_out<isect_tri_t> tri_rsp_data_i;
  sc_core::sc_out<octree::slot_t> tri_rsp_tag_i;

  SC_HAS_PROCESS(rt_octree_mem);
  explicit rt_octree_mem(sc_core::sc_module_name name);

  // Arms the memory for one run (call while the simulation is paused): empties
  // the ports and reseeds them. The image must outlive the run.
  void start(const fx::OctreeImage& image, int latency, int jitter, uint64_t seed);
  // Stops serving (no responses, requests ignored) until the next start().
  void stop() { image_ = nullptr; }

 private:
  void edge();

  const fx::OctreeImage* image_ = nullptr;
  fx::MemoryReadPort node_, idx_, tri_;  // timing: sw/golden/stimulus.h
  uint64_t cycle_ = 0;
  bool readyWritten_ = false;  // req_ready is constant 1
  // Wire images packed on first use in a run (a group is read many times):
  // fx::packChildGroup by node index, fx::packWire by triangle id.
  std::vector<uint32_t> groupWire_, triWire_;
  std::vector<uint8_t> groupPacked_, triPacked_;
  // The response ports' values, reused (an sc_bv allocates when constructed).
  octree::group_t groupPort_{};
  isect_tri_t triPort_{};
};

}  // namespace lancer::sc
