#pragma once

#include <array>
#include <cstdint>


#include "bvh/rt_bvh_unit.h"
#include "common/rt_walk_model.h"
#include "golden/bvh.h"

namespace lancer::sc {

// rt_bvh_model: hand-written cycle model of rtl/bvh/rt_bvh.sv, meant to match
// it cycle for cycle and bit for bit at its ports; docs/bvh-unit.md,
// "Micro-architecture of rt_bvh", is the contract (slot registers and state
// machine, the box tester's stages, the pop lane). The shell's work
// (rt_trav_shell: allocation, arbiters, FIFOs, credits, u_isect, closest hits,
// exit tests, results) is rt_trav_shell_model's, without RegRsp (node and
// triangle responses are used in the cycle they arrive); this model holds the
// walk of rt_bvh_slots.sv, the box tester rt_bvh_box.sv as a delay line of
// BVH_BOX_LATENCY cycles, and its setup (rt_mirror_pairs.sv).
//
//   cycle() once per rising edge (the shell's clock(); its reset() calls
//           resetWalk()): the cycle as an outline of named steps, each deciding from
//           the registers at the start of the cycle and the inputs.
//
// No arithmetic is duplicated: the per-ray setup is fx::BvhRaySetup, the box
// test fx::boxTest (on the planes fx::bvhPlane makes of the node response's
// fields, read in place), the cull rule fx::culledBy, the closest-hit order
// fx::closerResult, the test fx::intersect — the golden model's code,
// scheduled as the RTL schedules it.
class rt_bvh_model : public rt_walk_model<rt_bvh_model, rt_bvh_unit, /*RegRsp=*/false> {
  friend rt_walk_model;
  enum class State : uint8_t { Free, Setup, Enter, NodeReq, WaitNode, Box, Fetch, Pop, Check, Done };

  // A candidate node: its reference and its entry parameter.
  struct Candidate {
    fx::BvhRef ref;
    fx::u128 entry = 0;
  };

  // One slot's registers (docs/bvh-unit.md, "Slot registers"; the ray and its
  // closest hit are the shell's).
  struct Slot {
    State state = State::Free;
    fx::BvhRaySetup setup;  // o', mirror, active, pair, C, dominant
    bool anyHit = false;
    bool hitSeen = false;   // a result of the ray was a hit
    Candidate cur;
    int sp = 0;
    uint32_t block = 0;       // the treelet block of the last interior node entered
    bool suspending = false;  // DONE: the walk is set aside, not over
  };
  // The stacks of all slots, one memory as in the RTL (and apart from the
  // slots' registers, which every cycle reads: they stay small and near).
  using Stack = std::array<Candidate, fx::kBvhStackDepth>;

  // rt_bvh_box's answer for one node response, BVH_BOX_LATENCY cycles later.
  struct BoxAnswer {
    bool valid = false;
    int slot = -1;
    std::array<fx::BoxHit, fx::kBvhWidth> hit{};
    std::array<fx::BvhRef, fx::kBvhWidth> child{};
  };

  // The steps of a cycle (seq), each named for what it does.
  void cycle() override;
  void resetWalk() override;
  wants_t wants() const;
  int grantPop(int popping);
  BoxAnswer testNode();
  void visit(int k);
  void requestNode(int k);
  void absorbResult(const rt_isect_result& res);
  void check(int k);
  void takeBoxAnswer(const BoxAnswer& a);
  void pop(int k);
  void finishLeaves(const slot_mask& finishing);
  void load(int k);
  void candidate(int k, const Candidate& c);
  void enter(int k);
  walk_in suspendedWalk(int k) const;
  State& stateOf(int k) { return slots_[size_t(k)].state; }
  void mark(int k, State st, bool join);

  std::array<Slot, N> slots_{};
  std::array<Stack, N> stacks_{};
  // Slots by what they wait for: the want vectors, and fin_ (FETCH with every
  // result in: it ends in the next cycle).
  slot_mask enter_, nodeWant_, checkWant_, pop_, done_, fetch_, fin_;
  rt_rr_arb_model<N> popArb_{};
  int popGranted_ = -1;  // the pop lane's grant of the previous cycle: that slot pops now
  rt_sparse_delay_line<BoxAnswer, size_t(fx::kBvhBoxLatency)> boxLine_;  // u_box
};

}  // namespace lancer::sc
