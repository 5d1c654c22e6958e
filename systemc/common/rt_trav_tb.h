#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <systemc>

#include "base/rt_gated_clock.h"
#include "common/rt_record_bits.h"
#include "common/rt_trav_ports.h"
#include "common/rt_trav_stream.h"
#include "common/rt_trav_unit.h"
#include "golden/primitives.h"
#include "isect/rt_isect_types.h"
#include "memory/dispatcher.h"
#include "memory/system.h"

namespace lancer::sc {

// rt_trav_side: everything a unit's environment drives and sees, with the
// RTL's port names: its clock (a gated 10 ns clock, u_clk, that runs only
// during a run of a chip that uses the unit), reset, configuration, the ray,
// result and visit streams, and the memory side of its three read ports.
template <class Unit>
class rt_trav_side : public sc_core::sc_module,
                     public rt_trav_unit_ports<Unit, sc_core::sc_out, sc_core::sc_in> {
 public:
  sc_core::sc_out<typename Unit::cfg_t> cfg_i{Unit::kNames.cfgPort};
  rt_gated_clock u_clk{"u_clk"};

  explicit rt_trav_side(sc_core::sc_module_name name) : sc_core::sc_module(name) { u_clk.clk_o(this->clk_i); }
};

// rt_trav_tb: the testbench and memory of a chip of traversal units (Unit: a
// traits class, common/rt_trav_unit.h), one rt_trav_side per unit it was
// built with; a run uses the first `units`. One SC_METHOD on the rising edge
// of the units' clocks (started together, so their edges coincide) does, in
// unit order, what the C++ Verilated devices' chip loop does
// (sw/driver/verilator_traversal_run.h), so that the same chip gives the
// same cycles whichever model runs its units:
//   - edges 0 .. RESET_CYCLES-1: reset, the configuration, every input idle;
//   - then, at the edge that ends cycle c: the end test (every ray has its
//     result, the memory system is idle, no unit has a visit on offer: the
//     run is over before cycle c); each unit's handshakes of cycle c
//     (rt_trav_stream::sample; a request the memory was ready for goes to
//     the memory system, one it was not counts as a stall); the memory
//     system's tick and the dispatcher's refill; the watchdog; then every
//     unit's stimulus of cycle c+1 (rt_trav_stream::drive) and its memory
//     responses and readiness.
// The node port's response carries Unit::node_packer's record at the
// address (a grid cell; an octree child group), the index and triangle ports
// one index-list entry and one triangle. An address outside the image is an
// SC_REPORT_ERROR (the device throws).
template <class Unit>
class rt_trav_tb : public sc_core::sc_module {
 public:
  static constexpr int RESET_CYCLES = 3;
  using image_t = typename Unit::image_t;
  using slot_t = typename Unit::slot_t;
  using mem_addr_t = typename Unit::mem_addr_t;

  sc_core::sc_vector<rt_trav_side<Unit>> sides;

  SC_HAS_PROCESS(rt_trav_tb);
  rt_trav_tb(sc_core::sc_module_name name, int units) : sc_core::sc_module(name), sides("side", size_t(units)) {
    for (int u = 0; u < units; ++u) streams_.emplace_back(Unit::kResFields, Unit::kVisitFields);
    units_.assign(size_t(units), {});
    SC_METHOD(edge);
    sensitive << sides[0].clk_i.pos();
    dont_initialize();
  }

  int capacity() const { return int(sides.size()); }

  // Arms the chip for one run of `units` units on `memory`; call while the
  // simulation is paused, then sc_start() until the clocks stop. The job, the
  // image and the memory must outlive the run.
  void start(const rt_trav_job& job, const image_t& image, mem::MemorySystem& memory, int units) {
    job_ = &job;
    image_ = &image;
    memory_ = &memory;
    active_ = units;
    cfg_ = Unit::config(image);
    nodes_.start(image);
    triWires_.start(image.triangles.size());
    quadricWires_.start(image.quadrics.size());
    dispatcher_.emplace(job.rays.size(), units, job.dispatchBatch);
    owner_.assign(job.rays.size(), -1);
    for (int u = 0; u < units; ++u) {
      streams_[size_t(u)].start(job, u, *dispatcher_, owner_);
      units_[size_t(u)] = {};
    }
    edge_ = 0;
    lastProgress_ = 0;
    error_.clear();
    finished_ = false;
    for (int u = 0; u < units; ++u) sides[size_t(u)].u_clk.start();
  }

  // What unit u counted in the last run.
  const rt_trav_tally& tally(int u) const { return streams_[size_t(u)].tally(); }
  // Empty unless the run was abandoned (a unit's stream error, the watchdog).
  std::string error() const {
    if (!error_.empty()) return error_;
    for (int u = 0; u < active_; ++u) {
      if (streams_[size_t(u)].failed()) return streams_[size_t(u)].tally().error;
    }
    return {};
  }
  bool finished() const { return finished_; }
  // Stops serving (the run failed in SystemC): the clocks stop after this edge.
  void stop() { finish(); }

 private:
  // What the testbench drives into a unit in the current cycle.
  struct Driven {
    bool resReady = false, visitReady = false;
    std::array<bool, 3> reqReady{true, true, true};
  };

  void finish() {
    finished_ = true;
    for (int u = 0; u < active_; ++u) {
      sides[size_t(u)].u_clk.stop();  // this was the last rising edge of the run
      quiet(sides[size_t(u)]);
    }
  }

  // Nothing offered, nothing taken, no memory response.
  static void quiet(rt_trav_side<Unit>& side) {
    side.ray_valid_i.write(false);
    side.res_ready_i.write(false);
    side.visit_ready_i.write(false);
    side.node_rsp_valid_i.write(false);
    side.idx_rsp_valid_i.write(false);
    side.tri_rsp_valid_i.write(false);
    side.quadric_rsp_valid_i.write(false);
  }

  // Edges 0 .. RESET_CYCLES-1 drive reset and the configuration; from edge
  // RESET_CYCLES on, the value written after edge e is sampled at edge e+1,
  // which ends cycle e - RESET_CYCLES.
  void edge() {
    if (finished_) return;
    const uint64_t edge = edge_++;
    if (edge < uint64_t(RESET_CYCLES)) {
      for (int u = 0; u < active_; ++u) idle(sides[size_t(u)]);
      return;
    }
    if (edge == uint64_t(RESET_CYCLES)) {
      for (int u = 0; u < active_; ++u) sides[size_t(u)].rst_ni.write(true);
      dispatcher_->refill();
      lastProgress_ = memory_->cycle();
    } else {
      if (over()) return finish();
      bool progress = false;
      for (int u = 0; u < active_; ++u) progress |= sample(u);
      if (!error().empty()) return finish();
      memory_->tick();
      dispatcher_->refill();
      if (progress) lastProgress_ = memory_->cycle();
      if (memory_->cycle() - lastProgress_ > job_->watchdogCycles) {
        error_ = fmt::format("no progress for {} cycles ({} of {} rays have results)", job_->watchdogCycles,
                             results(), job_->rays.size());
        return finish();
      }
    }
    for (int u = 0; u < active_; ++u) drive(u);
  }

  void idle(rt_trav_side<Unit>& side) {
    side.rst_ni.write(false);
    side.cfg_i.write(cfg_);
    side.cfg_slots_i.write(typename Unit::cfg_slots_t(job_->slots));
    quiet(side);
    side.node_req_ready_i.write(true);
    side.idx_req_ready_i.write(true);
    side.tri_req_ready_i.write(true);
  }

  uint64_t results() const {
    uint64_t n = 0;
    for (int u = 0; u < active_; ++u) n += streams_[size_t(u)].tally().results;
    return n;
  }

  // Before a cycle: every ray has its result, the memory is idle and no unit
  // offers a visit.
  bool over() const {
    if (results() != job_->rays.size() || !memory_->idle()) return false;
    for (int u = 0; u < active_; ++u) {
      if (sides[size_t(u)].visit_valid_o.read() || !streams_[size_t(u)].drained()) return false;
    }
    return true;
  }

  // Unit u's handshakes of the cycle that ends: its requests to the memory
  // system, its visits and results into the traces. True on progress.
  bool sample(int u) {
    rt_trav_side<Unit>& side = sides[size_t(u)];
    const Driven& driven = units_[size_t(u)];
    const uint64_t cycle = memory_->cycle();
    rt_trav_sample s;
    s.rayReady = side.ray_ready_o.read();
    s.resValid = side.res_valid_o.read();
    s.resReady = driven.resReady;
    s.visitValid = side.visit_valid_o.read();
    s.visitReady = driven.visitReady;
    request(u, s, mem::Port::Node, side.node_req_valid_o, side.node_req_addr_o, side.node_req_tag_o);
    request(u, s, mem::Port::Index, side.idx_req_valid_o, side.idx_req_addr_o, side.idx_req_tag_o);
    s.triQuadric = side.tri_req_valid_o.read() && side.tri_req_quadric_o.read();
    request(u, s, mem::Port::Triangle, side.tri_req_valid_o, side.tri_req_addr_o, side.tri_req_tag_o);
    s.quadricRsp = side.quadric_rsp_valid_i.read();
    s.perfIsectFire = side.perf_isect_fire_o.read();
    s.perfStepReady = side.perf_step_ready_o.read();
    std::array<uint32_t, size_t(fx::wireWords(Unit::RESULT_W))> resWire{};
    std::array<uint32_t, size_t(fx::wireWords(Unit::VISIT_W))> visitWire{};
    rt_trav_stream& stream = streams_[size_t(u)];
    if (s.resValid && stream.wantsData(s.resReady)) {
      fromPort<Unit::RESULT_W>(side.res_data_o.read(), resWire);
      s.resWire = resWire;
    }
    if (s.visitValid && stream.wantsData(s.visitReady)) {
      fromPort<Unit::VISIT_W>(side.visit_data_o.read(), visitWire);
      s.visitWire = visitWire;
    }
    return stream.sample(cycle, s);
  }

  void request(int u, rt_trav_sample& s, mem::Port port, const sc_core::sc_in<bool>& valid,
               const sc_core::sc_in<mem_addr_t>& addr, const sc_core::sc_in<slot_t>& tag) {
    const int p = int(port);
    s.req[p] = valid.read();
    s.reqReady[p] = units_[size_t(u)].reqReady[size_t(p)];
    if (!s.req[p]) return;
    s.addr[p] = uint32_t(addr.read());
    s.tag[p] = uint32_t(tag.read());
    if (s.reqReady[p]) {
      // A primitive read names its table by the entry's kind bit (mem::AddressMap::span).
      const bool quadric = port == mem::Port::Triangle && s.triQuadric;
      memory_->request(u, port, fx::primitiveEntry(s.addr[p], quadric), s.tag[p]);
    } else {
      memory_->blocked(u, port);
    }
  }

  // Unit u's inputs of the next cycle: its stimulus, its memory responses
  // and the memory's readiness.
  void drive(int u) {
    rt_trav_side<Unit>& side = sides[size_t(u)];
    rt_trav_stream& stream = streams_[size_t(u)];
    const rt_trav_stream::Drive d = stream.drive(memory_->cycle());
    if (d.newOffer) side.ray_data_i.write(job_->rays[stream.offered()]);
    side.ray_valid_i.write(d.rayValid);
    side.res_ready_i.write(d.resReady);
    side.visit_ready_i.write(d.visitReady);
    Driven& driven = units_[size_t(u)];
    driven.resReady = d.resReady;
    driven.visitReady = d.visitReady;

    uint32_t addr = 0, tag = 0;
    const bool node = memory_->response(u, mem::Port::Node, addr, tag);
    side.node_rsp_valid_i.write(node);
    if (node) {
      if (!nodes_.holds(addr)) outside(Unit::kNames.nodeTable, addr, nodes_.entries());
      assignPort<Unit::NODE_DATA_W>(nodePort_, nodes_.wire(addr));
      side.node_rsp_data_i.write(nodePort_);
      side.node_rsp_tag_i.write(slot_t(tag));
    }
    const bool idx = memory_->response(u, mem::Port::Index, addr, tag);
    side.idx_rsp_valid_i.write(idx);
    if (idx) {
      if (addr >= image_->indices.size()) outside("index list", addr, image_->indices.size());
      side.idx_rsp_data_i.write(typename Unit::idx_data_t(image_->indices[addr]));
      side.idx_rsp_tag_i.write(slot_t(tag));
    }
    // The primitive port: a triangle's record, or a quadric's (the request's kind bit).
    const bool primitive = memory_->response(u, mem::Port::Triangle, addr, tag);
    const bool tri = primitive && !fx::isQuadricEntry(addr);
    side.tri_rsp_valid_i.write(tri);
    side.quadric_rsp_valid_i.write(primitive && !tri);
    if (primitive && !tri) {
      const uint32_t place = fx::entryPlace(addr);
      if (place >= image_->quadrics.size()) outside("quadric table", place, image_->quadrics.size());
      assignPort<ISECT_QUADRIC_W>(quadricPort_, quadricWires_.wire(image_->quadrics, place));
      side.quadric_rsp_data_i.write(quadricPort_);
      side.quadric_rsp_tag_i.write(slot_t(tag));
    }
    if (tri) {
      if (addr >= image_->triangles.size()) outside("triangle table", addr, image_->triangles.size());
      assignPort<ISECT_TRI_W>(triPort_, triWires_.wire(image_->triangles, addr));
      side.tri_rsp_data_i.write(triPort_);
      side.tri_rsp_tag_i.write(slot_t(tag));
    }
    for (int p = 0; p < 3; ++p) driven.reqReady[size_t(p)] = memory_->ready(u, mem::Port(p));
    side.node_req_ready_i.write(driven.reqReady[0]);
    side.idx_req_ready_i.write(driven.reqReady[1]);
    side.tri_req_ready_i.write(driven.reqReady[2]);
  }

  void outside(const char* region, uint32_t addr, size_t size) {
    const std::string what = fmt::format("{} read at {} outside the image ({} entries)", region, addr, size);
    SC_REPORT_ERROR(name(), what.c_str());
    throw std::out_of_range(what);  // not reached when errors throw (sw/driver/systemc_kernel.cpp)
  }

  const rt_trav_job* job_ = nullptr;
  const image_t* image_ = nullptr;
  mem::MemorySystem* memory_ = nullptr;
  int active_ = 0;
  typename Unit::cfg_t cfg_{};
  std::vector<rt_trav_stream> streams_;
  std::vector<Driven> units_;
  std::optional<Dispatcher> dispatcher_;
  std::vector<int> owner_;
  uint64_t edge_ = 0, lastProgress_ = 0;
  std::string error_;
  bool finished_ = false;
  typename Unit::node_packer nodes_;
  // The primitive tables' wire images, each record packed on first use in a run.
  template <size_t Words>
  struct packed_table {
    std::vector<uint32_t> words;
    std::vector<uint8_t> packed;
    void start(size_t records) {
      packed.assign(records, 0);
      words.resize(records * Words);
    }
    template <class Record>
    std::span<const uint32_t> wire(const std::vector<Record>& table, uint32_t place) {
      const std::span<uint32_t> out(words.data() + size_t(place) * Words, Words);
      if (!packed[place]) {
        fx::packWire(table[place], out);
        packed[place] = 1;
      }
      return out;
    }
  };
  packed_table<fx::kIsectTriWords> triWires_;
  packed_table<size_t(fx::wireWords(ISECT_QUADRIC_W))> quadricWires_;
  // The response ports' values, reused (an sc_bv allocates when constructed).
  typename Unit::node_data_t nodePort_{};
  isect_tri_t triPort_{};
  vl_port_t<ISECT_QUADRIC_W> quadricPort_{};
};

}  // namespace lancer::sc
