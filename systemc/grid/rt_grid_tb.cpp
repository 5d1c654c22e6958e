#include "grid/rt_grid_tb.h"

#include <array>

#include <fmt/format.h>

#include "golden/stimulus.h"

namespace lancer::sc {

rt_grid_tb::rt_grid_tb(sc_core::sc_module_name name)
    : sc_core::sc_module(name),
      clk_i("clk_i"),
      rst_ni("rst_ni"),
      cfg_res_i("cfg_res_i"),
      cfg_slots_i("cfg_slots_i"),
      ray_valid_i("ray_valid_i"),
      ray_ready_o("ray_ready_o"),
      ray_data_i("ray_data_i"),
      res_valid_o("res_valid_o"),
      res_ready_i("res_ready_i"),
      res_data_o("res_data_o"),
      visit_valid_o("visit_valid_o"),
      visit_ready_i("visit_ready_i"),
      visit_data_o("visit_data_o"),
      cell_req_valid_o("cell_req_valid_o"),
      cell_req_addr_o("cell_req_addr_o"),
      cell_req_tag_o("cell_req_tag_o"),
      cell_rsp_valid_i("cell_rsp_valid_i"),
      idx_req_valid_o("idx_req_valid_o"),
      idx_req_addr_o("idx_req_addr_o"),
      idx_req_tag_o("idx_req_tag_o"),
      idx_rsp_valid_i("idx_rsp_valid_i"),
      tri_req_valid_o("tri_req_valid_o"),
      tri_req_addr_o("tri_req_addr_o"),
      tri_req_tag_o("tri_req_tag_o"),
      tri_rsp_valid_i("tri_rsp_valid_i"),
      perf_isect_fire_o("perf_isect_fire_o"),
      perf_step_ready_o("perf_step_ready_o") {
  SC_METHOD(clock);
  sensitive << start_;
  dont_initialize();

  SC_METHOD(stream);
  sensitive << clk_i.pos();
  dont_initialize();
}

void rt_grid_tb::start(const rt_grid_job& job) {
  job_ = &job;
  tally_ = rt_grid_tally{};
  tally_.busy = true;
  tally_.resultCells.assign(job.rays.size(), 0);
  finished_.assign(job.rays.size(), 0);
  edge_ = 0;
  rng_.seed(job.seed);
  idleThreshold_ = fx::Coin::thresholdFor(job.inputIdleProbability);
  stallThreshold_ = fx::Coin::thresholdFor(job.outputStallProbability);
  offered_ = 0;
  offering_ = started_ = false;
  firstCycle_ = lastProgress_ = 0;
  for (int p = 0; p < 3; ++p) requests_[p] = responses_[p] = 0;
  running_ = true;
  start_.notify(sc_core::SC_ZERO_TIME);
}

void rt_grid_tb::clock() {
  const bool level = clk_i.read();
  if (!level && !running_) return;  // at rest, low, until the next start()
  clk_i.write(!level);
  next_trigger(sc_core::sc_time(CLOCK_PERIOD_NS / 2, sc_core::SC_NS));
}

void rt_grid_tb::abandon(const std::string& why) {
  tally_.error = why;
  finish();
}

void rt_grid_tb::finish() {
  tally_.busy = false;
  running_ = false;  // this was the last rising edge of the run
  ray_valid_i.write(false);
  res_ready_i.write(false);
  visit_ready_i.write(false);
}

// Edges 0 .. RESET_CYCLES-1 drive reset and the configuration; from edge
// RESET_CYCLES on, the value written after edge e is sampled at edge e+1, which
// ends cycle e - RESET_CYCLES.
void rt_grid_tb::stream() {
  const uint64_t edge = edge_++;
  if (edge < RESET_CYCLES) {
    const fx::GridRes& r = job_->image->res;
    rst_ni.write(false);
    cfg_res_i.write(cfg_res_t(uint32_t(r[0]) | (uint32_t(r[1]) << GRID_RESOLUTION_W) |
                              (uint32_t(r[2]) << (2 * GRID_RESOLUTION_W))));
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
    // VerilatorGridDevice's loop condition, evaluated at the start of this cycle.
    bool memoryIdle = true;
    for (int p = 0; p < 3; ++p) memoryIdle = memoryIdle && requests_[p] == responses_[p];
    if (tally_.results == job_->rays.size() && memoryIdle && !visit_valid_o.read()) {
      finish();
      return;
    }
    sample(cycle);
    if (!tally_.busy) return;
  }
  drive(edge - RESET_CYCLES);
}

void rt_grid_tb::sample(uint64_t cycle) {
  const size_t n = job_->rays.size();
  const bool rayFire = offering_ && ray_ready_o.read();
  bool progress = rayFire;
  GridCycle c;
  const bool tracing = job_->trace != nullptr && started_;
  if (cell_req_valid_o.read()) {
    ++requests_[0];
    ++tally_.nodeReads;
    c.cellReq = true;
    c.cellAddr = uint32_t(cell_req_addr_o.read());
    c.cellTag = uint32_t(cell_req_tag_o.read());
  }
  if (idx_req_valid_o.read()) {
    ++requests_[1];
    ++tally_.indexReads;
    c.idxReq = true;
    c.idxAddr = uint32_t(idx_req_addr_o.read());
    c.idxTag = uint32_t(idx_req_tag_o.read());
  }
  if (tri_req_valid_o.read()) {
    ++requests_[2];
    ++tally_.triangleReads;
    c.triReq = true;
    c.triAddr = uint32_t(tri_req_addr_o.read());
    c.triTag = uint32_t(tri_req_tag_o.read());
  }
  responses_[0] += cell_rsp_valid_i.read();
  responses_[1] += idx_rsp_valid_i.read();
  responses_[2] += tri_rsp_valid_i.read();
  if (perf_isect_fire_o.read()) {
    ++tally_.isectTests;
    c.perfIsectFire = true;
    progress = true;
  }
  if (started_ && perf_step_ready_o.read()) {
    ++tally_.stepReadyCycles;
    c.perfStepReady = true;
  }
  const bool visitReady = visit_ready_i.read(), resReady = res_ready_i.read();
  if (visit_valid_o.read()) {
    std::array<uint32_t, size_t(fx::wireWords(GRID_VISIT_W))> wire{};
    fromPort<GRID_VISIT_W>(visit_data_o.read(), wire);
    if (visitReady) {
      std::array<fx::u128, fx::valueCount(fx::kGridVisitFields)> v{};
      fx::unpackFields(fx::kGridVisitFields, wire, v);
      const size_t k = size_t(v[0]);
      if (k >= offered_) return abandon(fmt::format("a visit record for ray {} that is not in flight", k));
      (*job_->traces)[k].visits.push_back(uint32_t(v[1]));
      ++tally_.visits;
      tally_.cycles = cycle - firstCycle_ + 1;
      progress = true;
    }
    if (tracing) c.visitData.assign(wire.begin(), wire.end());
  }
  if (res_valid_o.read()) {
    std::array<uint32_t, size_t(fx::wireWords(GRID_RESULT_W))> wire{};
    fromPort<GRID_RESULT_W>(res_data_o.read(), wire);
    if (resReady) {
      std::array<fx::u128, fx::valueCount(fx::kGridResFields)> v{};
      fx::unpackFields(fx::kGridResFields, wire, v);
      const size_t k = size_t(v[0]);
      if (k >= offered_ || finished_[k]) {
        return abandon(fmt::format("a result for ray {} that is not in flight", k));
      }
      finished_[k] = 1;
      tally_.resultCells[k] = uint32_t(v[1]);
      fx::GridTrace& t = (*job_->traces)[k];
      t.tests = uint64_t(v[2]);
      if (v[3]) {
        fx::IsectResult hit;
        hit.rayId = job_->rayIds[k];
        hit.primId = uint32_t(v[4]);
        hit.hit = true;
        hit.tNum = v[5];
        hit.det = v[6];
        hit.uNum = v[7];
        hit.vNum = v[8];
        t.hit = hit;
      }
      ++tally_.results;
      tally_.cycles = cycle - firstCycle_ + 1;
      progress = true;
    }
    if (tracing) c.resData.assign(wire.begin(), wire.end());
  }
  if (tracing) {
    c.cycle = cycle - firstCycle_;
    c.rayValid = offering_;
    c.rayReady = ray_ready_o.read();
    c.resValid = res_valid_o.read();
    c.resReady = resReady;
    c.visitValid = visit_valid_o.read();
    c.visitReady = visitReady;
    job_->trace->push_back(std::move(c));
  }
  if (rayFire) {
    offering_ = false;
    ++offered_;
    ++tally_.accepted;
  }
  if (progress) lastProgress_ = cycle;
  if (cycle - lastProgress_ > job_->watchdogCycles) {
    abandon(fmt::format("no progress for {} cycles ({} of {} rays accepted, {} results)", job_->watchdogCycles,
                        offered_, n, tally_.results));
  }
}

void rt_grid_tb::drive(uint64_t cycle) {
  if (!offering_ && offered_ < job_->rays.size() && !coin(idleThreshold_)) {
    ray_data_i.write(job_->rays[offered_]);
    offering_ = true;
    if (!started_) {
      started_ = true;
      firstCycle_ = cycle;
      lastProgress_ = cycle;
    }
  }
  ray_valid_i.write(offering_);
  res_ready_i.write(!coin(stallThreshold_));
  visit_ready_i.write(!coin(stallThreshold_));
}

}  // namespace lancer::sc
