#include "common/rt_trav_stream.h"

#include <array>
#include <stdexcept>

#include <fmt/format.h>

#include "golden/stimulus.h"
#include "memory/config.h"

namespace lancer::sc {

namespace {

// {ray_id, elements, tests, quadric tests, hit, prim_id, t_num, det, u_num, v_num} and {ray_id, element id}.
constexpr size_t kResValues = 10;
constexpr size_t kVisitValues = 2;

}  // namespace

rt_trav_stream::rt_trav_stream(std::span<const fx::FieldSpec> resFields, std::span<const fx::FieldSpec> visitFields)
    : resFields_(resFields), visitFields_(visitFields), visitSlots_(fieldSlots<kVisitValues>(visitFields)) {
  if (fx::valueCount(resFields) != kResValues || fx::valueCount(visitFields) != kVisitValues ||
      visitSlots_[0].width > 64 || visitSlots_[1].width > 64) {
    throw std::logic_error("rt_trav_stream: unexpected result or visit record layout");
  }
}

void rt_trav_stream::start(const rt_trav_job& job, int unit, Dispatcher& dispatcher, std::vector<int>& owner) {
  job_ = &job;
  unit_ = unit;
  dispatcher_ = &dispatcher;
  owner_ = &owner;
  tally_ = rt_trav_tally{};
  tally_.resultSteps.assign(job.rays.size(), 0);
  finished_.assign(job.rays.size(), 0);
  rng_.seed(mem::unitSeed(job.seed, unit));
  idleThreshold_ = fx::Coin::thresholdFor(job.inputIdleProbability);
  stallThreshold_ = fx::Coin::thresholdFor(job.outputStallProbability);
  current_ = 0;
  offering_ = started_ = false;
}

void rt_trav_stream::abandon(const std::string& why) {
  if (tally_.error.empty()) tally_.error = fmt::format("unit {}: {}", unit_, why);
}

bool rt_trav_stream::sample(uint64_t cycle, const rt_trav_sample& s) {
  const bool rayFire = offering_ && s.rayReady;
  bool progress = rayFire;
  uint64_t* const reads[3] = {&tally_.nodeReads, &tally_.indexReads, &tally_.triangleReads};
  for (int p = 0; p < 3; ++p) *reads[p] += s.req[p] && s.reqReady[p];
  tally_.quadricTests += s.quadricRsp;
  if (s.perfIsectFire) {
    ++tally_.isectTests;
    progress = true;
  }
  if (started_) tally_.stepReadyCycles += s.perfStepReady;
  if (s.visitValid && s.visitReady) {
    const size_t k = size_t(getBits64(s.visitWire.data(), visitSlots_[0].lsb, visitSlots_[0].width));
    if (!mine(k, false)) {
      abandon(fmt::format("a visit record for ray {} that is not in flight", k));
      return false;
    }
    (*job_->traces)[k].visits.push_back(
        uint32_t(getBits64(s.visitWire.data(), visitSlots_[1].lsb, visitSlots_[1].width)));
    ++tally_.visits;
    tally_.lastCycle = cycle;
    progress = true;
  }
  if (s.resValid && s.resReady) {
    std::array<fx::u128, kResValues> v{};
    fx::unpackFields(resFields_, s.resWire, v);
    const size_t k = size_t(v[0]);
    if (!mine(k, true)) {
      abandon(fmt::format("a result for ray {} that is not in flight", k));
      return false;
    }
    finished_[k] = 1;
    tally_.resultSteps[k] = fx::takeTraversalResult(v, job_->rayIds[k], (*job_->traces)[k]);
    ++tally_.results;
    tally_.lastCycle = cycle;
    progress = true;
  }
  if (tally_.accepted > tally_.results) ++tally_.busyCycles;
  if (tracing()) {
    TraversalCycle c;
    c.cycle = cycle - tally_.firstCycle;
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
    if (c.triReq) c.triAddr = s.addr[TRIANGLE], c.triTag = s.tag[TRIANGLE], c.triQuadric = s.triQuadric;
    c.perfIsectFire = s.perfIsectFire;
    c.perfStepReady = s.perfStepReady;
    if (s.resValid) c.resData.assign(s.resWire.begin(), s.resWire.end());
    if (s.visitValid) c.visitData.assign(s.visitWire.begin(), s.visitWire.end());
    job_->trace->push_back(std::move(c));
  }
  if (rayFire) {
    offering_ = false;
    (*owner_)[current_] = unit_;
    dispatcher_->taken(unit_);
    ++tally_.accepted;
  }
  return progress;
}

rt_trav_stream::Drive rt_trav_stream::drive(uint64_t cycle) {
  Drive d;
  if (!offering_ && dispatcher_->holds(unit_, cycle) && !coin(idleThreshold_)) {
    d.newOffer = true;
    offering_ = true;
    current_ = dispatcher_->next(unit_);
    if (!started_) {
      started_ = true;
      tally_.started = true;
      tally_.firstCycle = cycle;
    }
  }
  d.rayValid = offering_;
  d.resReady = !coin(stallThreshold_);
  d.visitReady = !coin(stallThreshold_);
  return d;
}

}  // namespace lancer::sc
