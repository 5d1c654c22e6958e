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
#include "memory/dispatcher.h"
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
  std::vector<TraversalCycle>* trace = nullptr;       // optional per-cycle port trace (unit 0's)
  uint64_t watchdogCycles = 1'000'000;                // give up after this many cycles without progress
  int dispatchBatch = 32;                             // the chip's dispatcher (memory/dispatcher.h)
};

// What the testbench counted for one unit (TraversalRunStats' semantics;
// cycles after reset, numbered as the chip's memory system numbers them).
struct rt_trav_tally {
  bool started = false;
  uint64_t firstCycle = 0, lastCycle = 0;  // first ray offered, last result or visit taken
  uint64_t busyCycles = 0;                 // cycles with a ray of this unit in flight
  uint64_t accepted = 0, results = 0, visits = 0;
  uint64_t nodeReads = 0, indexReads = 0, triangleReads = 0;
  uint64_t isectTests = 0;       // cycles with perf_isect_fire_o
  uint64_t quadricTests = 0;     // quadric responses (each one test of rt_quadric)
  uint64_t stepReadyCycles = 0;  // cycles with perf_step_ready_o
  std::vector<uint32_t> resultSteps;  // the result record's element count (cells, nodes) per ray (of this unit)
  std::string error;
};

// The ports of a traversal unit in one cycle, as the testbench samples them at
// the rising edge that ends it (the three memory ports: node or cell, index, triangle).
struct rt_trav_sample {
  bool rayReady = false;
  bool resValid = false, resReady = false;
  bool visitValid = false, visitReady = false;
  bool req[3] = {};
  bool reqReady[3] = {true, true, true};  // the memory took the request (req && reqReady)
  uint32_t addr[3] = {}, tag[3] = {};
  bool triQuadric = false;  // tri_req_quadric_o: the triangle port's read is of the quadric table
  bool rsp[3] = {};
  bool quadricRsp = false;  // quadric_rsp_valid_i (the primitive port's response is a quadric's)
  bool perfIsectFire = false, perfStepReady = false;
  std::span<const uint32_t> resWire, visitWire;  // when the testbench asked for them (wantsData)
};

// rt_trav_stream: the testbench logic of one unit of a chip, without SystemC
// ports, so that the chip's testbench (rt_trav_tb) only moves values between
// its ports and one of these per unit. It replays the C++ Verilated devices'
// UnitRun cycle by cycle:
//   - sample(): the cycle's handshakes are counted (reads from the requests
//     the memory took; tests from perf_isect_fire_o; step-ready cycles from
//     perf_step_ready_o; visits and results taken and decoded into the
//     traces; busy cycles);
//   - drive(): the next cycle's stimulus from one std::mt19937_64 (seeded
//     with mem::unitSeed of the job's seed): the idle draw (only with no ray on
//     offer and one held from the dispatcher) before the result stall draw
//     before the visit stall draw, a draw only for a non-zero probability
//     (fx::Coin).
// The end of a run and the watchdog are the chip's (rt_trav_tb).
// Result records are {ray_id, elements, tests, hit, prim_id, t_num, det,
// u_num, v_num} (grid_res_t, octree_res_t), visits {ray_id, element id}.
class rt_trav_stream {
 public:
  enum Port { NODE = 0, INDEX = 1, TRIANGLE = 2 };

  rt_trav_stream(std::span<const fx::FieldSpec> resFields, std::span<const fx::FieldSpec> visitFields);

  // One run of unit `unit`, offering the rays `dispatcher` hands it; `owner`
  // (one entry per ray, shared by the units) records which unit took each.
  void start(const rt_trav_job& job, int unit, Dispatcher& dispatcher, std::vector<int>& owner);
  const rt_trav_job& job() const { return *job_; }
  const rt_trav_tally& tally() const { return tally_; }
  bool failed() const { return !tally_.error.empty(); }

  // Whether sample() needs the data of a valid result / visit this cycle.
  bool wantsData(bool ready) const { return ready || tracing(); }
  // True if the unit made progress (a ray accepted, a test, a visit or a result).
  bool sample(uint64_t cycle, const rt_trav_sample& s);
  // No ray of this unit in flight, none on offer.
  bool drained() const { return tally_.accepted == tally_.results && !offering_; }

  struct Drive {
    bool newOffer = false;  // write rays[offered()] to ray_data_i
    bool rayValid = false, resReady = false, visitReady = false;
  };
  Drive drive(uint64_t cycle);
  // The ray on offer (its index in the job).
  size_t offered() const { return current_; }

  void abandon(const std::string& why);

 private:
  bool tracing() const { return job_->trace != nullptr && unit_ == 0 && started_; }
  // Ray k of a visit or result record: one this unit took (visits may trail
  // the ray's result; a second result is an error).
  bool mine(size_t k, bool result) const {
    return k < owner_->size() && (*owner_)[k] == unit_ && !(result && finished_[k]);
  }
  bool coin(uint64_t threshold) { return threshold != 0 && rng_() < threshold; }

  std::span<const fx::FieldSpec> resFields_, visitFields_;
  std::array<rt_field_slot, 2> visitSlots_{};  // {ray_id, element id}: read on every visit
  const rt_trav_job* job_ = nullptr;
  rt_trav_tally tally_;
  std::mt19937_64 rng_;
  uint64_t idleThreshold_ = 0, stallThreshold_ = 0;
  int unit_ = 0;
  Dispatcher* dispatcher_ = nullptr;
  std::vector<int>* owner_ = nullptr;
  size_t current_ = 0;
  bool offering_ = false, started_ = false;
  std::vector<uint8_t> finished_;
};

}  // namespace lancer::sc
