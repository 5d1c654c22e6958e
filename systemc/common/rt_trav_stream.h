#pragma once

#include <array>
#include <cstdint>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "common/rt_record_bits.h"
#include "common/rt_trav_cycle.h"
#include "golden/records.h"
#include "golden/trace.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// One run of a traversal-unit testbench (rt_octree_tb; the same stimulus as
// rt_grid_tb and the C++ Verilated devices).
struct rt_trav_job {
  std::vector<isect_ray_t> rays;   // ray k carries ray_id = k on the port
  std::vector<uint32_t> rayIds;    // the rays' own ids, for the hits of the traces
  uint32_t slots = 1;              // cfg_slots_i
  double inputIdleProbability = 0.0;
  double outputStallProbability = 0.0;
  uint64_t seed = 1;
  std::vector<fx::TraversalTrace>* traces = nullptr;  // rays.size() entries, filled in
  std::vector<TraversalCycle>* trace = nullptr;       // optional per-cycle port trace
  uint64_t watchdogCycles = 1'000'000;                // give up after this many cycles without progress
};

// What the testbench counted (TraversalRunStats' semantics; cycles after reset).
struct rt_trav_tally {
  uint64_t cycles = 0;  // first ray offered .. last result or visit taken, both included
  uint64_t accepted = 0, results = 0, visits = 0;
  uint64_t nodeReads = 0, indexReads = 0, triangleReads = 0;
  uint64_t isectTests = 0;       // cycles with perf_isect_fire_o
  uint64_t stepReadyCycles = 0;  // cycles with perf_step_ready_o
  std::vector<uint32_t> resultSteps;  // the result record's element count (cells, nodes) per ray
  bool busy = false;
  std::string error;
};

// The ports of a traversal unit in one cycle, as the testbench samples them at
// the rising edge that ends it (the three memory ports: node or cell, index, triangle).
struct rt_trav_sample {
  bool rayReady = false;
  bool resValid = false, resReady = false;
  bool visitValid = false, visitReady = false;
  bool req[3] = {};
  uint32_t addr[3] = {}, tag[3] = {};
  bool rsp[3] = {};
  bool perfIsectFire = false, perfStepReady = false;
  std::span<const uint32_t> resWire, visitWire;  // when the testbench asked for them (wantsData)
};

// rt_trav_stream: the testbench logic of a traversal unit, without SystemC
// ports, so that every unit's testbench module (rt_octree_tb; rt_grid_tb could
// use it too) only moves values between its ports and this class. It replays
// the C++ Verilated devices' run loop cycle by cycle:
//   - over(): the loop ends before a cycle in which every result is in, no
//     memory response is outstanding and visit_valid_o is low;
//   - sample(): the cycle's handshakes are counted (reads from the request
//     valids, since req_ready is always 1; tests from perf_isect_fire_o;
//     step-ready cycles from perf_step_ready_o; visits and results taken and
//     decoded into the traces);
//   - drive(): the next cycle's stimulus from one std::mt19937_64(seed): the
//     idle draw (only with no ray on offer and rays left) before the result
//     stall draw before the visit stall draw, a draw only for a non-zero
//     probability (fx::Coin).
// Result records are {ray_id, elements, tests, hit, prim_id, t_num, det,
// u_num, v_num} (grid_res_t, octree_res_t), visits {ray_id, element id}.
class rt_trav_stream {
 public:
  enum Port { NODE = 0, INDEX = 1, TRIANGLE = 2 };

  rt_trav_stream(std::span<const fx::FieldSpec> resFields, std::span<const fx::FieldSpec> visitFields);

  void start(const rt_trav_job& job);
  const rt_trav_job& job() const { return *job_; }
  const rt_trav_tally& tally() const { return tally_; }
  bool busy() const { return tally_.busy; }

  // The end test, at the start of a cycle.
  bool over(bool visitValid) const;
  // Whether sample() needs the data of a valid result / visit this cycle.
  bool wantsData(bool ready) const { return ready || tracing(); }
  void sample(uint64_t cycle, const rt_trav_sample& s);

  struct Drive {
    bool newOffer = false;  // write rays[offered()] to ray_data_i
    bool rayValid = false, resReady = false, visitReady = false;
  };
  Drive drive(uint64_t cycle);
  size_t offered() const { return offered_; }

  void finish();
  void abandon(const std::string& why);

 private:
  bool tracing() const { return job_->trace != nullptr && started_; }
  bool coin(uint64_t threshold) { return threshold != 0 && rng_() < threshold; }

  std::span<const fx::FieldSpec> resFields_, visitFields_;
  std::array<rt_field_slot, 2> visitSlots_{};  // {ray_id, element id}: read on every visit
  const rt_trav_job* job_ = nullptr;
  rt_trav_tally tally_;
  std::mt19937_64 rng_;
  uint64_t idleThreshold_ = 0, stallThreshold_ = 0;
  size_t offered_ = 0;
  bool offering_ = false, started_ = false;
  uint64_t firstCycle_ = 0, lastProgress_ = 0;
  uint64_t requests_[3] = {}, responses_[3] = {};
  std::vector<uint8_t> finished_;
};

}  // namespace lancer::sc
