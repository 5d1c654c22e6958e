#pragma once

// The part of a walk model that keeps its slots in a state register each, with
// the request vectors derived from it (rt_bvh_model, rt_octree_model; the grid
// model derives its wants from several registers and refreshes them itself):
// the state change, the cycle's common tail and the done grant.
//
// Derived provides
//   State                         its states (an enum with Free and Setup)
//   State& stateOf(int k)         slot k's state register
//   void mark(int k, State, bool join)  the sets a slot in that state belongs to, joined or left
//   void load(int k)              SETUP's end: the slot's per-ray setup
//   walk_in suspendedWalk(int k)  (a unit that suspends walks) the done slot's
//                                 walk record if it is suspended, else none

#include "common/rt_trav_shell_model.h"

namespace lancer::sc {

template <class Derived, class Unit, bool RegRsp>
class rt_walk_model : public rt_trav_shell_model<Unit, RegRsp> {
 protected:
  rt_walk_model() : rt_trav_shell_model<Unit, RegRsp>(rt_isect_impl::model) {}

  // The state register with the sets derived from it. (A template: Derived's
  // State is not known where this class is.)
  template <class State>
  void setState(int k, State next) {
    Derived& d = derived();
    d.mark(k, d.stateOf(k), false);
    d.stateOf(k) = next;
    d.mark(k, next, true);
  }

  // The end of every cycle, after the walk's own steps: the done grant (the
  // result record; the slot free), the slot leaving SETUP, the allocation,
  // then the shell's end of the cycle (a step is ready if a slot is in
  // `entering`, the walk's set of slots that want to enter an element, as
  // the registers stand at the end of the cycle).
  void endWalkCycle(const rt_trav_grants& g, const typename rt_trav_shell_model<Unit, RegRsp>::slot_mask& entering) {
    if (g.done >= 0) {
      if constexpr (Unit::kSuspends) {
        this->finishRay(g.done, derived().suspendedWalk(g.done));
      } else {
        this->finishRay(g.done);
      }
      setState(g.done, Derived::State::Free);
    }
    if (this->loadSlot() >= 0) derived().load(this->loadSlot());
    if (g.alloc >= 0) setState(g.alloc, Derived::State::Setup);
    this->endCycle(g, entering.any());
  }

 private:
  Derived& derived() { return static_cast<Derived&>(*this); }
};

}  // namespace lancer::sc
