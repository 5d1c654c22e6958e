#include "isect/rt_pipe_tb.h"

#include <fmt/format.h>

#include "golden/stimulus.h"

namespace lancer::sc {

template <class Kind>
rt_pipe_tb<Kind>::rt_pipe_tb(sc_core::sc_module_name name)
    : sc_core::sc_module(name) {
  u_clk.clk_o(this->clk_i);

  SC_METHOD(stream);
  sensitive << this->clk_i.pos();
  dont_initialize();

  SC_METHOD(monitor);
  sensitive << this->clk_i.pos();
  dont_initialize();
}

template <class Kind>
void rt_pipe_tb<Kind>::start(const rt_pipe_job<Kind>& job) {
  job_ = &job;
  tally_ = rt_pipe_tally{};
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

template <class Kind>
void rt_pipe_tb<Kind>::abandon(const std::string& why) {
  tally_.error = why;
  tally_.busy = false;
  u_clk.stop();
}

// Edges 0 .. RESET_CYCLES-1 drive reset (low at edges 1 .. RESET_CYCLES); from
// edge RESET_CYCLES on, the value written after edge e is sampled at edge e+1,
// which ends cycle e - RESET_CYCLES. Both partners sample the ports as they were
// before the edge and write what the next cycle sees.
template <class Kind>
void rt_pipe_tb<Kind>::stream() {
  const uint64_t edge = edge_++;
  produce(edge);
  consume(edge);
}

template <class Kind>
void rt_pipe_tb<Kind>::produce(uint64_t edge) {
  if (edge < RESET_CYCLES) {
    this->rst_ni.write(false);
    this->req_valid_i.write(false);
    return;
  }
  bool holding = false;
  if (edge == RESET_CYCLES) {
    this->rst_ni.write(true);
  } else if (this->req_valid_i.read()) {
    if (this->req_ready_o.read()) {
      ++tally_.accepted;
      ++next_;
    } else {
      ++tally_.inputStalls;
      holding = true;
    }
  }
  if (holding) return;  // the offered request stays, unchanged
  if (next_ < job_->rays.size() && !coin(idleThreshold_)) {
    this->req_ray_i.write(job_->rays[next_]);
    Kind::prim(*this).write(job_->prims[next_]);
    this->req_valid_i.write(true);
    if (!offered_) {
      offered_ = true;
      tally_.firstOffer = edge - RESET_CYCLES;
    }
  } else {
    this->req_valid_i.write(false);
  }
}

template <class Kind>
void rt_pipe_tb<Kind>::consume(uint64_t edge) {
  if (edge < RESET_CYCLES) {
    this->res_ready_i.write(false);
    return;
  }
  if (edge > RESET_CYCLES) {
    const uint64_t cycle = edge - RESET_CYCLES - 1;
    if (this->res_valid_o.read() && this->res_ready_i.read()) {
      fx::ResWire wire;
      fromPort<ISECT_RES_W>(this->res_data_o.read(), wire);
      fx::unpackResult(wire, job_->results->emplace_back());
      lastProgress_ = cycle;
      if (++tally_.taken == job_->rays.size()) {
        tally_.lastTake = cycle;
        tally_.busy = false;
        u_clk.stop();  // this was the last rising edge of the run
        this->res_ready_i.write(false);
        return;
      }
    } else if (cycle - lastProgress_ > job_->watchdogCycles) {
      abandon(fmt::format("no result for {} cycles ({} of {} taken, {} accepted)",
                          job_->watchdogCycles, tally_.taken, job_->rays.size(), tally_.accepted));
      return;
    }
  }
  this->res_ready_i.write(!coin(stallThreshold_));
}

template <class Kind>
void rt_pipe_tb<Kind>::monitor() {
  const uint64_t edge = monitorEdge_++;
  if (job_->trace == nullptr || edge <= RESET_CYCLES || monitorTaken_ >= job_->rays.size()) return;
  IsectCycle c;
  c.cycle = edge - RESET_CYCLES - 1;
  c.reqValid = this->req_valid_i.read();
  c.reqReady = this->req_ready_o.read();
  c.resValid = this->res_valid_o.read();
  c.resReady = this->res_ready_i.read();
  if (c.resValid) c.resData = fromPort<ISECT_RES_W>(this->res_data_o.read());
  if (c.resValid && c.resReady) ++monitorTaken_;
  job_->trace->push_back(std::move(c));
}

template struct rt_pipe_tb<isect_kind>;
template struct rt_pipe_tb<quadric_kind>;

}  // namespace lancer::sc
