#include "octree/rt_octree_tb.h"

#include <array>

namespace lancer::sc {

using namespace octree;

rt_octree_tb::rt_octree_tb(sc_core::sc_module_name name)
    : sc_core::sc_module(name),
      clk_i("clk_i"),
      rst_ni("rst_ni"),
      cfg_slots_i("cfg_slots_i"),
      cfg_root_i("cfg_root_i"),
      ray_valid_i("ray_valid_i"),
      ray_ready_o("ray_ready_o"),
      ray_data_i("ray_data_i"),
      res_valid_o("res_valid_o"),
      res_ready_i("res_ready_i"),
      res_data_o("res_data_o"),
      visit_valid_o("visit_valid_o"),
      visit_ready_i("visit_ready_i"),
      visit_data_o("visit_data_o"),
      node_req_valid_o("node_req_valid_o"),
      node_req_addr_o("node_req_addr_o"),
      node_req_tag_o("node_req_tag_o"),
      node_rsp_valid_i("node_rsp_valid_i"),
      idx_req_valid_o("idx_req_valid_o"),
      idx_req_addr_o("idx_req_addr_o"),
      idx_req_tag_o("idx_req_tag_o"),
      idx_rsp_valid_i("idx_rsp_valid_i"),
      tri_req_valid_o("tri_req_valid_o"),
      tri_req_addr_o("tri_req_addr_o"),
      tri_req_tag_o("tri_req_tag_o"),
      tri_rsp_valid_i("tri_rsp_valid_i"),
      perf_isect_fire_o("perf_isect_fire_o"),
      perf_step_ready_o("perf_step_ready_o"),
      stream_(fx::kOctreeResFields, fx::kOctreeVisitFields) {
  SC_METHOD(clock);
  sensitive << start_;
  dont_initialize();

  SC_METHOD(stream);
  sensitive << clk_i.pos();
  dont_initialize();
}

void rt_octree_tb::start(const rt_octree_job& job) {
  job_ = &job;
  stream_.start(job);
  edge_ = 0;
  resReady_ = visitReady_ = false;
  running_ = true;
  start_.notify(sc_core::SC_ZERO_TIME);
}

void rt_octree_tb::clock() {
  const bool level = clk_i.read();
  if (!level && !running_) return;  // at rest, low, until the next start()
  clk_i.write(!level);
  next_trigger(halfPeriod_);
}

void rt_octree_tb::finish() {
  stream_.finish();
  running_ = false;  // this was the last rising edge of the run
  ray_valid_i.write(false);
  res_ready_i.write(false);
  visit_ready_i.write(false);
}

// Edges 0 .. RESET_CYCLES-1 drive reset and the configuration; from edge
// RESET_CYCLES on, the value written after edge e is sampled at edge e+1, which
// ends cycle e - RESET_CYCLES.
void rt_octree_tb::stream() {
  const uint64_t edge = edge_++;
  if (edge < RESET_CYCLES) {
    rst_ni.write(false);
    std::array<uint32_t, size_t(fx::wireWords(NODE_W))> root{};
    const fx::OctreeNode& r = job_->image->nodes.at(0);
    const fx::u128 values[] = {r.leaf ? 1u : 0u, r.count, r.first};
    fx::packFields(fx::kOctreeNodeFields, values, root);
    cfg_root_i.write(toPort<NODE_W>(root));
    cfg_slots_i.write(cfg_slots_t(job_->slots));
    ray_valid_i.write(false);
    res_ready_i.write(false);
    visit_ready_i.write(false);
    return;
  }
  if (edge == RESET_CYCLES) {
    rst_ni.write(true);
  } else {
    const uint64_t cycle = edge - RESET_CYCLES - 1;
    if (stream_.over(visit_valid_o.read())) {
      finish();
      return;
    }
    sample(cycle);
    if (!stream_.busy()) {
      finish();
      return;
    }
  }
  drive(edge - RESET_CYCLES);
}

void rt_octree_tb::sample(uint64_t cycle) {
  rt_trav_sample s;
  s.rayReady = ray_ready_o.read();
  s.resValid = res_valid_o.read();
  s.resReady = resReady_;
  s.visitValid = visit_valid_o.read();
  s.visitReady = visitReady_;
  s.req[rt_trav_stream::NODE] = node_req_valid_o.read();
  s.req[rt_trav_stream::INDEX] = idx_req_valid_o.read();
  s.req[rt_trav_stream::TRIANGLE] = tri_req_valid_o.read();
  if (s.req[rt_trav_stream::NODE]) {
    s.addr[rt_trav_stream::NODE] = uint32_t(node_req_addr_o.read());
    s.tag[rt_trav_stream::NODE] = uint32_t(node_req_tag_o.read());
  }
  if (s.req[rt_trav_stream::INDEX]) {
    s.addr[rt_trav_stream::INDEX] = uint32_t(idx_req_addr_o.read());
    s.tag[rt_trav_stream::INDEX] = uint32_t(idx_req_tag_o.read());
  }
  if (s.req[rt_trav_stream::TRIANGLE]) {
    s.addr[rt_trav_stream::TRIANGLE] = uint32_t(tri_req_addr_o.read());
    s.tag[rt_trav_stream::TRIANGLE] = uint32_t(tri_req_tag_o.read());
  }
  s.rsp[rt_trav_stream::NODE] = node_rsp_valid_i.read();
  s.rsp[rt_trav_stream::INDEX] = idx_rsp_valid_i.read();
  s.rsp[rt_trav_stream::TRIANGLE] = tri_rsp_valid_i.read();
  s.perfIsectFire = perf_isect_fire_o.read();
  s.perfStepReady = perf_step_ready_o.read();
  std::array<uint32_t, size_t(fx::wireWords(RESULT_W))> resWire{};
  std::array<uint32_t, size_t(fx::wireWords(VISIT_W))> visitWire{};
  if (s.resValid && stream_.wantsData(s.resReady)) {
    fromPort<RESULT_W>(res_data_o.read(), resWire);
    s.resWire = resWire;
  }
  if (s.visitValid && stream_.wantsData(s.visitReady)) {
    fromPort<VISIT_W>(visit_data_o.read(), visitWire);
    s.visitWire = visitWire;
  }
  stream_.sample(cycle, s);
}

void rt_octree_tb::drive(uint64_t cycle) {
  const rt_trav_stream::Drive d = stream_.drive(cycle);
  if (d.newOffer) ray_data_i.write(job_->rays[stream_.offered()]);
  ray_valid_i.write(d.rayValid);
  res_ready_i.write(d.resReady);
  visit_ready_i.write(d.visitReady);
  resReady_ = d.resReady;
  visitReady_ = d.visitReady;
}

}  // namespace lancer::sc
