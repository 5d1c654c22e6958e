#include "octree/rt_octree_model.h"

#include <algorithm>
#include <array>

#include <fmt/format.h>

#include "common/rt_record_bits.h"

namespace lancer::sc {

namespace {

constexpr size_t kNodeWords = size_t(fx::wireWords(rt_octree_unit::NODE_W));
constexpr size_t kGroupWords = size_t(fx::wireWords(rt_octree_unit::NODE_DATA_W));
static_assert(fx::valueCount(fx::kOctreeNodeFields) == 3, "octree_node_t layout changed");

fx::OctreeNode unpackNode(const uint32_t* wire) {  // {leaf, count, first}
  return fx::OctreeNode{getField<fx::kOctreeNodeFields, 0>(wire) != 0,
                        uint32_t(getField<fx::kOctreeNodeFields, 2>(wire)),
                        uint32_t(getField<fx::kOctreeNodeFields, 1>(wire))};
}

bool negative(const fx::OctT& t) { return t.inf < 0 || (t.inf == 0 && t.value < 0); }

bool anyNegative(const std::array<fx::OctT, 3>& t) { return negative(t[0]) || negative(t[1]) || negative(t[2]); }

constexpr fx::OctT kMinusInf{0, -1}, kPlusInf{0, 1};

}  // namespace

// One cycle: the shell's grants and responses, then the walk's events — at
// most one state-changing event per slot, each reading that slot's registers
// as they were at the start of the cycle —, then the shell's registers and outputs.
void rt_octree_model::cycle() {
  const rt_trav_grants g = grant(wants());
  const lanes_t lanes = granted_;  // granted in the previous cycle: they advance now
  granted_ = grantLanes(lanes);
  const slot_mask self = self_;
  const int nodeSlot = nodeResponseSlot();
  const rt_isect_result res = intersect(fetch_);

  if (g.visit >= 0) visit(g.visit);
  if (g.node >= 0) requestGroup(g.node);
  if (nodeSlot >= 0) takeGroup(nodeSlot);
  if (res.valid && res.last) self_.set(res.slot);  // the leaf's last result: CHECK in the next cycle
  if (g.check >= 0) check(g.check);
  advanceLanes(lanes);
  actOnTheirOwn(self);
  endWalkCycle(g, enter_);
}

void rt_octree_model::resetWalk() {
  for (Slot& s : slots_) s.state = State::Free;
  for (slot_mask* m : {&enter_, &nodeWant_, &checkWant_, &advWant_, &done_, &fetch_, &self_}) m->clear();
  advArb_.fill(rt_rr_arb_model<N>{});
  granted_.fill(-1);
}

// rt_octree_slots' want vectors: the state masks.
rt_octree_model::wants_t rt_octree_model::wants() const {
  return wants_t{.node = nodeWant_, .visit = enter_, .check = checkWant_, .done = done_, .expect = fetch_};
}

// The advance lanes' grants: lane l over what the lanes before it left.
rt_octree_model::lanes_t rt_octree_model::grantLanes(const lanes_t& advancing) {
  lanes_t lanes{};
  slot_mask left = advWant_;
  for (const int k : advancing) {
    if (k >= 0) left.reset(k);
  }
  for (size_t l = 0; l < lanes.size(); ++l) {
    lanes[l] = advArb_[l].pick(left);
    if (lanes[l] >= 0) {
      left.reset(lanes[l]);
      advArb_[l].ack(lanes[l]);
    }
  }
  return lanes;
}

// The node response's slot, or -1 (the RTL's assertion: the slot waits for a group).
int rt_octree_model::nodeResponseSlot() {
  const node_rsp rsp = nodeResponse();
  if (!rsp.valid) return -1;
  const State st = rsp.slot < N ? slots_[size_t(rsp.slot)].state : State::Free;
  if (st != State::WaitGroup && st != State::WaitRefill) {
    fail(fmt::format("node response for slot {}, which does not wait for one", rsp.slot));
  }
  return rsp.slot;
}

// ENTER on the visit grant: the visit record, then the node's kind decides.
void rt_octree_model::visit(int k) {
  pushVisit(k, slots_[size_t(k)].nodeId);
  enter(k);
}

// GROUP_REQ: the node's child group; REFILL_REQ: the group of the level the walk is in.
void rt_octree_model::requestGroup(int k) {
  Slot& s = slots_[size_t(k)];
  const bool group = s.state == State::GroupReq;
  const uint32_t address = group ? s.rec.first : s.stack[size_t(s.depth - 1)].first;
  pushNode(k, address);
  s.block = address >> cfg_block_shift_i.read();
  setState(k, group ? State::WaitGroup : State::WaitRefill);
}

void rt_octree_model::takeGroup(int k) {
  Slot& s = slots_[size_t(k)];
  std::array<uint32_t, kGroupWords> wire{};
  fromValue<rt_octree_unit::NODE_DATA_W>(*nodeResponse().data, wire);
  for (size_t i = 0; i < size_t(fx::kOctreeChildren); ++i) s.group[i] = unpackNode(wire.data() + i * kNodeWords);
  s.groupValid = true;
  if (s.state == State::WaitGroup) {
    setState(k, State::Descend);
  } else {
    s.rec = s.group[size_t(s.stack[size_t(s.depth - 1)].child ^ s.setup.mirror)];
    setState(k, State::Enter);
  }
}

// The exit test; when the leaf does not end the ray, its lane advances the slot.
void rt_octree_model::check(int k) {
  const Slot& s = slots_[size_t(k)];
  const rt_closest_record& h = hit(k);
  if (h.settled() || fx::hitWithin(h.best, s.t1, s.setup)) {
    setState(k, State::Done);
  } else {
    advance(k);
  }
}

void rt_octree_model::advanceLanes(const lanes_t& lanes) {
  for (size_t l = 0; l < lanes.size(); ++l) {
    if (lanes[l] < 0) continue;
    advance(lanes[l]);
  }
}

// DESCEND, and FETCH with every result in (-> CHECK), as the cycle began.
void rt_octree_model::actOnTheirOwn(const slot_mask& self) {
  self.forEach([&](int k) {
    switch (slots_[size_t(k)].state) {
      case State::Descend: descend(k); break;
      case State::Fetch: setState(k, State::Check); break;
      default: break;
    }
  });
}

// The sets a slot in state `st` belongs to, joined or left.
void rt_octree_model::mark(int k, State st, bool join) {
  const auto put = [&](slot_mask& m) { join ? m.set(k) : m.reset(k); };
  switch (st) {
    case State::Enter: put(enter_); break;
    case State::GroupReq:
    case State::RefillReq: put(nodeWant_); break;
    case State::Fetch:
      put(fetch_);
      if (!join) self_.reset(k);  // (joined by the leaf's last result)
      break;
    case State::Check:
      if (join) {
        put(hit(k).wantsCheck() ? checkWant_ : advWant_);
      } else {
        checkWant_.reset(k);
        advWant_.reset(k);
      }
      break;
    case State::Descend: put(self_); break;
    case State::Next: put(advWant_); break;
    case State::Done: put(done_); break;
    default: break;
  }
}

// SETUP -> ENTER | DONE at the end of accept + OCTREE_SETUP_LATENCY: the
// per-ray setup and the root test; or a resumed walk's registers, in
// GROUP_REQ for the child group it descends into, in that group's block.
void rt_octree_model::load(int k) {
  Slot& s = slots_[size_t(k)];
  s.groupValid = false;
  s.suspending = false;
  if (const auto values = resumedWalkValues()) {
    const fx::QRay ray = loadRay(k, fx::walkHitOf(*values, uint32_t(k)));
    const fx::OctreeWalk walk = fx::octreeWalkOf(*values, ray);
    s.setup = fx::OctreeRaySetup::setup(ray);
    s.t0 = walk.t0;
    s.t1 = walk.t1;
    s.depth = int(walk.stack.size());
    for (size_t e = 0; e < walk.stack.size(); ++e) s.stack[e] = StackEntry{walk.stack[e].first, walk.stack[e].child};
    s.block = walk.group >> cfg_block_shift_i.read();
    s.rec = fx::OctreeNode{false, walk.group, 0};
    setState(k, State::GroupReq);
    return;
  }
  s.setup = fx::OctreeRaySetup::setup(loadRay(k));
  s.t0 = s.setup.t0;
  s.t1 = s.setup.t1;
  s.nodeId = 0;
  std::array<uint32_t, size_t(fx::wireWords(rt_octree_unit::CFG_W))> root{};
  fromValue<rt_octree_unit::CFG_W>(cfg_i.read(), root);
  s.rec = unpackNode(root.data());
  s.depth = 0;
  s.block = s.rec.leaf ? 0 : s.rec.first >> cfg_block_shift_i.read();
  const fx::OctT enter = std::max({s.t0[0], s.t0[1], s.t0[2]});
  const fx::OctT leave = std::min({s.t1[0], s.t1[1], s.t1[2]});
  setState(k, enter < leave ? State::Enter : State::Done);
}

// GROUP_REQ, unless suspension is on and the node's child group lies in
// another block than the slot's with at most OCTREE_SUSPEND_LEVELS levels on
// the stack: then DONE, suspended (its result carries the walk).
void rt_octree_model::requestOrSuspend(int k) {
  Slot& s = slots_[size_t(k)];
  s.suspending = cfg_suspend_i.read() && (s.rec.first >> cfg_block_shift_i.read()) != s.block &&
                 s.depth <= fx::kOctreeSuspendLevels;
  setState(k, s.suspending ? State::Done : State::GroupReq);
}

// The done slot's walk record, if it is suspended: the closest hit so far,
// the group it reads first, the node's parameters, the stack
// (fx::octreeWalkValues' packing).
rt_octree_model::walk_in rt_octree_model::suspendedWalk(int k) const {
  const Slot& s = slots_[size_t(k)];
  if (!s.suspending) return {};
  fx::OctreeWalk walk;
  if (hit(k).hasHit) walk.trace.hit = hit(k).best;
  walk.next = fx::OctreeWalk::Next::Descend;
  walk.group = s.rec.first;
  walk.t0 = s.t0;
  walk.t1 = s.t1;
  for (int e = 0; e < s.depth; ++e) walk.stack.push_back(fx::OctreeLevel{s.stack[size_t(e)].first, s.stack[size_t(e)].child});
  return suspendedRecord(fx::octreeWalkValues(walk));
}

// ENTER on the visit grant (the visit record is pushed by the caller).
void rt_octree_model::enter(int k) {
  const Slot& s = slots_[size_t(k)];
  if (!s.rec.leaf) {
    requestOrSuspend(k);
  } else if (s.rec.count > 0) {
    startRun(k, s.rec.first, s.rec.count);
    setState(k, State::Fetch);
  } else {
    setState(k, State::Check);
  }
}

// DESCEND: into the first child the ray enters, from the parameters and the group.
void rt_octree_model::descend(int k) {
  Slot& s = slots_[size_t(k)];
  if (s.depth >= MAX_STACK) fail(fmt::format("slot {}: an interior node at depth {} (the stack has {} levels)", k,
                                             s.depth, MAX_STACK));
  std::array<fx::OctT, 3> tm{};
  for (int a = 0; a < 3; ++a) {
    if (s.setup.active[a]) {
      tm[a] = fx::OctT{(s.t0[a].value + s.t1[a].value) >> 1, 0};  // exact: the sum is even
    } else {
      // The node's mid-plane on this axis, from the path (mirrored frame): the
      // node's lower corner is the sum of the upper halves taken on the way down.
      int64_t lo = 0;
      for (int j = 0; j < s.depth; ++j) {
        if ((s.stack[size_t(j)].child >> (2 - a)) & 1) lo += int64_t(1) << (fx::kPosBits - 1 - j);
      }
      const int64_t mid = lo + (int64_t(1) << (fx::kPosBits - 1 - s.depth));
      tm[a] = s.setup.origin[a] < mid ? kPlusInf : kMinusInf;
    }
  }
  const int c = fx::firstChild(s.t0, tm);
  s.stack[size_t(s.depth)] = StackEntry{s.rec.first, uint8_t(c)};
  ++s.depth;
  for (int a = 0; a < 3; ++a) {
    if ((c >> (2 - a)) & 1) {
      s.t0[a] = tm[a];
    } else {
      s.t1[a] = tm[a];
    }
  }
  const int stored = c ^ s.setup.mirror;
  s.nodeId = s.rec.first + uint32_t(stored);
  s.rec = s.group[size_t(stored)];
  setState(k, anyNegative(s.t1) ? State::Next : State::Enter);
}

// advance (in an advance lane: NEXT, CHECK without a hit; in the exit test's
// lane: CHECK when the leaf does not end the ray): the sibling or up.
void rt_octree_model::advance(int k) {
  Slot& s = slots_[size_t(k)];
  if (s.depth == 0) {
    setState(k, State::Done);
    return;
  }
  StackEntry& top = s.stack[size_t(s.depth - 1)];
  const int c = top.child;
  const int next = fx::nextChild(c, s.t1);  // exit axis: argmin t1, exact ties to the later axis
  if (next < fx::kOctreeChildren) {
    const int x = (next ^ c) == 4 ? 0 : ((next ^ c) == 2 ? 1 : 2);
    const fx::OctT t1 = s.t1[x];
    s.t1[x] = fx::OctT{2 * t1.value - s.t0[x].value, 0};
    s.t0[x] = t1;
    top.child = uint8_t(next);
    const int stored = next ^ s.setup.mirror;
    s.nodeId = top.first + uint32_t(stored);
    if (s.groupValid) s.rec = s.group[size_t(stored)];
    setState(k, anyNegative(s.t1) ? State::Next : (s.groupValid ? State::Enter : State::RefillReq));
    return;
  }
  for (int y = 0; y < 3; ++y) {
    if (!s.setup.active[y]) continue;
    if ((c >> (2 - y)) & 1) {
      s.t0[y] = fx::OctT{2 * s.t0[y].value - s.t1[y].value, 0};
    } else {
      s.t1[y] = fx::OctT{2 * s.t1[y].value - s.t0[y].value, 0};
    }
  }
  --s.depth;
  s.groupValid = false;
  setState(k, s.depth == 0 ? State::Done : State::Next);
}

}  // namespace lancer::sc
