#include "isect/rt_isect_tb.h"

#include <fmt/format.h>

#include "golden/stimulus.h"

namespace lancer::sc {

rt_isect_tb::rt_isect_tb(sc_core::sc_module_name name)
    : sc_core::sc_module(name) {
  u_clk.clk_o(clk_i);

  SC_METHOD(stream);
  sensitive << clk_i.pos();
  dont_initialize();

  SC_METHOD(monitor);
  sensitive << clk_i.pos();
  dont_initialize();
}

void rt_isect_tb::start(const rt_isect_job& job) {
  job_ = &job;
  tally_ = rt_isect_tally{};
  tally_.busy = true;
  edge_ = monitorEdge_ = 0;
  rng_.seed(job.seed);
  idleThreshold_ = fx::Coin::thresholdFor(job.inputIdleProbability);
  stallThreshold_ = fx::Coin::thresholdFor(job.outputStallProbability);
  next_ = 0;
  offered_ = false;
  lastProgress_ = 0;
  monitorTaken_ = 0;
  u_clk.start();
}

void rt_isect_tb::abandon(const std::string& why) {
  tally_.error = why;
  tally_.busy = false;
  u_clk.stop();
}

// Edges 0 .. RESET_CYCLES-1 drive reset (low at edges 1 .. RESET_CYCLES); from
// edge RESET_CYCLES on, the value written after edge e is sampled at edge e+1,
// which ends cycle e - RESET_CYCLES. Both partners sample the ports as they were
// before the edge and write what the next cycle sees.
void rt_isect_tb::stream() {
  const uint64_t edge = edge_++;
  produce(edge);
  consume(edge);
}

void rt_isect_tb::produce(uint64_t edge) {
  if (edge < RESET_CYCLES) {
    rst_ni.write(false);
    req_valid_i.write(false);
    return;
  }
  bool holding = false;
  if (edge == RESET_CYCLES) {
    rst_ni.write(true);
  } else if (req_valid_i.read()) {
    if (req_ready_o.read()) {
      ++tally_.accepted;
      ++next_;
    } else {
      ++tally_.inputStalls;
      holding = true;
    }
  }
  if (holding) return;  // the offered request stays, unchanged
  if (next_ < job_->rays.size() && !coin(idleThreshold_)) {
    req_ray_i.write(job_->rays[next_]);
    req_tri_i.write(job_->tris[next_]);
    req_valid_i.write(true);
    if (!offered_) {
      offered_ = true;
      tally_.firstOffer = edge - RESET_CYCLES;
    }
  } else {
    req_valid_i.write(false);
  }
}

void rt_isect_tb::consume(uint64_t edge) {
  if (edge < RESET_CYCLES) {
    res_ready_i.write(false);
    return;
  }
  if (edge > RESET_CYCLES) {
    const uint64_t cycle = edge - RESET_CYCLES - 1;
    if (res_valid_o.read() && res_ready_i.read()) {
      fx::ResWire wire;
      fromPort<ISECT_RES_W>(res_data_o.read(), wire);
      fx::unpackResult(wire, job_->results->emplace_back());
      lastProgress_ = cycle;
      if (++tally_.taken == job_->rays.size()) {
        tally_.lastTake = cycle;
        tally_.busy = false;
        u_clk.stop();  // this was the last rising edge of the run
        res_ready_i.write(false);
        return;
      }
    } else if (cycle - lastProgress_ > job_->watchdogCycles) {
      abandon(fmt::format("no result for {} cycles ({} of {} taken, {} accepted)",
                          job_->watchdogCycles, tally_.taken, job_->rays.size(), tally_.accepted));
      return;
    }
  }
  res_ready_i.write(!coin(stallThreshold_));
}

void rt_isect_tb::monitor() {
  const uint64_t edge = monitorEdge_++;
  if (job_->trace == nullptr || edge <= RESET_CYCLES || monitorTaken_ >= job_->rays.size()) return;
  IsectCycle c;
  c.cycle = edge - RESET_CYCLES - 1;
  c.reqValid = req_valid_i.read();
  c.reqReady = req_ready_o.read();
  c.resValid = res_valid_o.read();
  c.resReady = res_ready_i.read();
  if (c.resValid) c.resData = fromPort<ISECT_RES_W>(res_data_o.read());
  if (c.resValid && c.resReady) ++monitorTaken_;
  job_->trace->push_back(std::move(c));
}

}  // namespace lancer::sc
