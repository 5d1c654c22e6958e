#include "common/rt_trav_stream.h"

#include <array>
#include <stdexcept>

#include <fmt/format.h>

#include "golden/stimulus.h"

namespace lancer::sc {

namespace {

// {ray_id, elements, tests, hit, prim_id, t_num, det, u_num, v_num} and {ray_id, element id}.
constexpr size_t kResValues = 9;
constexpr size_t kVisitValues = 2;

}  // namespace

rt_trav_stream::rt_trav_stream(std::span<const fx::FieldSpec> resFields, std::span<const fx::FieldSpec> visitFields)
    : resFields_(resFields), visitFields_(visitFields), visitSlots_(fieldSlots<kVisitValues>(visitFields)) {
  if (fx::valueCount(resFields) != kResValues || fx::valueCount(visitFields) != kVisitValues ||
      visitSlots_[0].width > 64 || visitSlots_[1].width > 64) {
    throw std::logic_error("rt_trav_stream: unexpected result or visit record layout");
  }
}

void rt_trav_stream::start(const rt_trav_job& job) {
  job_ = &job;
  tally_ = rt_trav_tally{};
  tally_.busy = true;
  tally_.resultSteps.assign(job.rays.size(), 0);
  finished_.assign(job.rays.size(), 0);
  rng_.seed(job.seed);
  idleThreshold_ = fx::Coin::thresholdFor(job.inputIdleProbability);
  stallThreshold_ = fx::Coin::thresholdFor(job.outputStallProbability);
  offered_ = 0;
  offering_ = started_ = false;
  firstCycle_ = lastProgress_ = 0;
  for (int p = 0; p < 3; ++p) requests_[p] = responses_[p] = 0;
}

bool rt_trav_stream::over(bool visitValid) const {
  bool memoryIdle = true;
  for (int p = 0; p < 3; ++p) memoryIdle = memoryIdle && requests_[p] == responses_[p];
  return tally_.results == job_->rays.size() && memoryIdle && !visitValid;
}

void rt_trav_stream::finish() { tally_.busy = false; }

void rt_trav_stream::abandon(const std::string& why) {
  tally_.error = why;
  finish();
}

void rt_trav_stream::sample(uint64_t cycle, const rt_trav_sample& s) {
  const size_t n = job_->rays.size();
  const bool rayFire = offering_ && s.rayReady;
  bool progress = rayFire;
  uint64_t* const reads[3] = {&tally_.nodeReads, &tally_.indexReads, &tally_.triangleReads};
  for (int p = 0; p < 3; ++p) {
    if (s.req[p]) {
      ++requests_[p];
      ++*reads[p];
    }
    responses_[p] += s.rsp[p];
  }
  if (s.perfIsectFire) {
    ++tally_.isectTests;
    progress = true;
  }
  tally_.stepReadyCycles += s.perfStepReady;
  if (s.visitValid && s.visitReady) {
    const size_t k = size_t(getBits64(s.visitWire.data(), visitSlots_[0].lsb, visitSlots_[0].width));
    if (k >= offered_) return abandon(fmt::format("a visit record for ray {} that is not in flight", k));
    (*job_->traces)[k].visits.push_back(
        uint32_t(getBits64(s.visitWire.data(), visitSlots_[1].lsb, visitSlots_[1].width)));
    ++tally_.visits;
    tally_.cycles = cycle - firstCycle_ + 1;
    progress = true;
  }
  if (s.resValid && s.resReady) {
    std::array<fx::u128, kResValues> v{};
    fx::unpackFields(resFields_, s.resWire, v);
    const size_t k = size_t(v[0]);
    if (k >= offered_ || finished_[k]) return abandon(fmt::format("a result for ray {} that is not in flight", k));
    finished_[k] = 1;
    tally_.resultSteps[k] = fx::takeTraversalResult(v, job_->rayIds[k], (*job_->traces)[k]);
    ++tally_.results;
    tally_.cycles = cycle - firstCycle_ + 1;
    progress = true;
  }
  if (tracing()) {
    TraversalCycle c;
    c.cycle = cycle - firstCycle_;
    c.rayValid = offering_;
    c.rayReady = s.rayReady;
    c.resValid = s.resValid;
    c.resReady = s.resReady;
    c.visitValid = s.visitValid;
    c.visitReady = s.visitReady;
    c.nodeReq = s.req[NODE];
    c.idxReq = s.req[INDEX];
    c.triReq = s.req[TRIANGLE];
    if (c.nodeReq) c.nodeAddr = s.addr[NODE], c.nodeTag = s.tag[NODE];
    if (c.idxReq) c.idxAddr = s.addr[INDEX], c.idxTag = s.tag[INDEX];
    if (c.triReq) c.triAddr = s.addr[TRIANGLE], c.triTag = s.tag[TRIANGLE];
    c.perfIsectFire = s.perfIsectFire;
    c.perfStepReady = s.perfStepReady;
    if (s.resValid) c.resData.assign(s.resWire.begin(), s.resWire.end());
    if (s.visitValid) c.visitData.assign(s.visitWire.begin(), s.visitWire.end());
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

rt_trav_stream::Drive rt_trav_stream::drive(uint64_t cycle) {
  Drive d;
  if (!offering_ && offered_ < job_->rays.size() && !coin(idleThreshold_)) {
    d.newOffer = true;
    offering_ = true;
    if (!started_) {
      started_ = true;
      firstCycle_ = cycle;
      lastProgress_ = cycle;
    }
  }
  d.rayValid = offering_;
  d.resReady = !coin(stallThreshold_);
  d.visitReady = !coin(stallThreshold_);
  return d;
}

}  // namespace lancer::sc
