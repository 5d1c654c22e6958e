#pragma once

#include <array>
#include <cstdint>
#include <string>


#include "common/rt_walk_model.h"
#include "golden/octree.h"
#include "octree/rt_octree_unit.h"

namespace lancer::sc {

// rt_octree_model: hand-written cycle model of rtl/octree/rt_octree.sv, meant to
// match it cycle for cycle and bit for bit at its ports; docs/octree-unit.md,
// "Micro-architecture of rt_octree", is the contract (slot registers and state
// machine, arbiters, FIFOs, credits, rt_isect timing), and docs/systemc.md
// states how this model reads the points the text leaves open. The shell's
// work (rt_trav_shell: allocation, arbiters, FIFOs, credits, u_isect, closest
// hits, results) is rt_trav_shell_model's, without RegRsp (node and triangle
// responses are used in the cycle they arrive); this model holds the walk of
// rt_octree_slots.sv (its stack, child groups and advance lanes) and the setup
// of rt_octree_setup.sv.
//
//   cycle() once per rising edge (the shell's clock(); its reset() calls
//           resetWalk()): the cycle as an outline of named steps, each deciding from
//           the registers at the start of the cycle and the inputs.
//
// No arithmetic is duplicated: the per-ray setup is fx::OctreeRaySetup, the
// first child fx::firstChild, the successor fx::nextChild, the exit test
// fx::hitWithin, the closest-hit order fx::closerResult, the test fx::intersect
// — the golden model's code, scheduled as the RTL schedules it. The parameters
// move as the micro-architecture says (halvings down, 2·t1 − t0 sideways and up:
// no parameters on the stack).
//
// Speed: per-state slot masks (the want vectors, kept as the state changes);
// the arbiters find the next requester with bit scans, and only slots that act
// on their own in a cycle (DESCEND, FETCH with every result in) or are granted
// an advance lane are visited.
class rt_octree_model : public rt_walk_model<rt_octree_model, rt_octree_unit, /*RegRsp=*/false> {
  friend rt_walk_model;
  enum class State : uint8_t {
    Free, Setup, Enter, GroupReq, WaitGroup, Descend, Fetch, Check, Next, RefillReq, WaitRefill, Done
  };

  static constexpr int MAX_STACK = fx::kOctreeMaxDepth;  // P entries: levels 0 .. P-1
  static constexpr int ADV_LANES = 2;  // rt_octree's AdvLanes: shared advance lanes besides the exit test's

  struct StackEntry {
    uint32_t first = 0;  // the level's child-group base
    uint8_t child = 0;   // which of its children the walk is in (mirrored numbering)
  };

  // One slot's registers (docs/octree-unit.md, "Slot registers"; the ray and
  // its closest hit are the shell's).
  struct Slot {
    State state = State::Free;
    fx::OctreeRaySetup setup;         // a, o', active, common, dominant
    std::array<fx::OctT, 3> t0{}, t1{};  // the current node's parameters
    uint32_t nodeId = 0;
    fx::OctreeNode rec;
    int depth = 0;
    std::array<StackEntry, MAX_STACK> stack{};
    std::array<fx::OctreeNode, fx::kOctreeChildren> group{};
    bool groupValid = false;
    uint32_t block = 0;       // the treelet block of the last child group read (the root's at the start)
    bool suspending = false;  // DONE: the walk is set aside before a descent, not over
  };

  using lanes_t = std::array<int, ADV_LANES>;  // each advance lane's slot, or -1

  // The steps of a cycle (seq), each named for what it does.
  void cycle() override;
  void resetWalk() override;
  wants_t wants() const;
  // This cycle's lane grants (each arbiter's pointer moves past its grant).
  lanes_t grantLanes(const lanes_t& advancing);
  int nodeResponseSlot();
  void visit(int k);
  void requestGroup(int k);
  void takeGroup(int k);
  void check(int k);
  void advanceLanes(const lanes_t& lanes);
  void actOnTheirOwn(const slot_mask& self);
  void load(int k);
  State& stateOf(int k) { return slots_[size_t(k)].state; }
  void mark(int k, State st, bool join);
  void enter(int k);
  void descend(int k);
  void advance(int k);
  void requestOrSuspend(int k);
  walk_in suspendedWalk(int k) const;

  std::array<Slot, N> slots_{};
  // Slots by what they wait for or do this cycle.
  // advWant_: NEXT and CHECK without a hit, waiting for an advance lane;
  // self_: DESCEND and FETCH with every result in, acting on their own.
  slot_mask enter_, nodeWant_, checkWant_, advWant_, done_, fetch_, self_;
  std::array<rt_rr_arb_model<N>, ADV_LANES> advArb_{};  // lane l takes what lanes before it left
  // The lanes' grants of the previous cycle (rt_octree_slots registers them):
  // those slots advance in this cycle and are left out of its arbitration.
  lanes_t granted_{};
};

}  // namespace lancer::sc
