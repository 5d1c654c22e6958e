#include "bvh/rt_bvh_model.h"

#include <array>
#include <optional>

#include <fmt/format.h>

#include "common/rt_record_bits.h"

namespace lancer::sc {

namespace {

static_assert(fx::valueCount(fx::kBvhNodeFields) == 24, "bvh_node_t layout changed");
static_assert(fx::valueCount(fx::kBvhRefFields) == 3, "bvh_ref_t layout changed");
static_assert(fx::kBvhWidth == 2, "u_box tests two children");

// Value I of a node response (bvh_node_t: values in kBvhNodeFields order, arrays element 0 first).
template <size_t I>
int64_t nodeField(const uint32_t* wire) {
  return getField<fx::kBvhNodeFields, I>(wire);
}

// u_box on child C of a node response: its box's planes as BvhNode::childLo
// and childHi give them, read straight from the wire image (the node is not
// unpacked: this runs on every node response).
template <size_t C>
fx::BoxHit testChild(const fx::BvhRaySetup& ray, const uint32_t* wire) {
  std::array<int64_t, 3> lo, hi;
  [&]<size_t... A>(std::index_sequence<A...>) {
    ((lo[A] = fx::bvhPlane(nodeField<A>(wire), uint32_t(nodeField<6 + 3 * C + A>(wire)), int(nodeField<3 + A>(wire)))),
     ...);
    ((hi[A] = fx::bvhPlane(nodeField<A>(wire), uint32_t(nodeField<12 + 3 * C + A>(wire)), int(nodeField<3 + A>(wire)))),
     ...);
  }(std::make_index_sequence<3>{});
  return fx::boxTest(ray, lo, hi);
}

// Child C's reference in a node response.
template <size_t C>
fx::BvhRef childRef(const uint32_t* wire) {
  return fx::BvhRef{nodeField<18 + C>(wire) != 0, uint32_t(nodeField<20 + C>(wire)), uint32_t(nodeField<22 + C>(wire))};
}

fx::BvhRef unpackRef(const uint32_t* wire) {  // {leaf, count, first}
  return fx::BvhRef{getField<fx::kBvhRefFields, 0>(wire) != 0, uint32_t(getField<fx::kBvhRefFields, 1>(wire)),
                    uint32_t(getField<fx::kBvhRefFields, 2>(wire))};
}

}  // namespace

// One cycle: the shell's grants and responses, then the walk's events — at
// most one state-changing event per slot, each reading that slot's registers
// as they were at the start of the cycle —, then the shell's registers and outputs.
void rt_bvh_model::cycle() {
  const rt_trav_grants g = grant(wants());
  const int popping = popGranted_;  // granted in the previous cycle: it pops now
  popGranted_ = grantPop(popping);
  const slot_mask finishing = fin_;
  BoxAnswer answer;
  if (boxLine_.outValid()) answer = boxLine_.out();
  const BoxAnswer tested = testNode();
  boxLine_.push(tested.valid, tested);
  const rt_isect_result res = intersect(fetch_);

  if (g.visit >= 0) visit(g.visit);
  if (g.node >= 0) requestNode(g.node);
  if (res.valid) absorbResult(res);
  if (g.check >= 0) check(g.check);
  if (answer.valid) takeBoxAnswer(answer);
  if (popping >= 0) pop(popping);
  finishLeaves(finishing);
  endWalkCycle(g, enter_);
}

void rt_bvh_model::resetWalk() {
  for (Slot& s : slots_) s.state = State::Free;
  for (slot_mask* m : {&enter_, &nodeWant_, &checkWant_, &pop_, &done_, &fetch_, &fin_}) m->clear();
  popArb_ = rt_rr_arb_model<N>{};
  popGranted_ = -1;
  boxLine_.clear();
}

// rt_bvh_slots' want vectors: the state masks.
rt_bvh_model::wants_t rt_bvh_model::wants() const {
  return wants_t{.node = nodeWant_, .visit = enter_, .check = checkWant_, .done = done_, .expect = fetch_};
}

// The pop lane's grant (registered: the slot pops in the next cycle), over the
// slots in POP less the one popping now.
int rt_bvh_model::grantPop(int popping) {
  slot_mask want = pop_;
  if (popping >= 0) want.reset(popping);
  const int k = popArb_.pick(want);
  if (k >= 0) popArb_.ack(k);
  return k;
}

// u_box: the node response of this cycle, both children tested with the
// responding slot's ray; the answer leaves the delay line BVH_BOX_LATENCY cycles later.
rt_bvh_model::BoxAnswer rt_bvh_model::testNode() {
  const node_rsp rsp = nodeResponse();
  if (!rsp.valid) return {};
  if (rsp.slot >= N || slots_[size_t(rsp.slot)].state != State::WaitNode) {
    fail(fmt::format("node response for slot {}, which does not wait for one", rsp.slot));
  }
  const uint32_t* wire = wireOf<rt_bvh_unit::NODE_DATA_W>(*rsp.data).data();
  const fx::BvhRaySetup& ray = slots_[size_t(rsp.slot)].setup;
  BoxAnswer a;
  a.valid = true;
  a.slot = rsp.slot;
  a.hit = {testChild<0>(ray, wire), testChild<1>(ray, wire)};
  a.child = {childRef<0>(wire), childRef<1>(wire)};
  setState(rsp.slot, State::Box);
  return a;
}

// ENTER on the visit grant: the visit record, then the node's kind decides.
void rt_bvh_model::visit(int k) {
  Slot& s = slots_[size_t(k)];
  pushVisit(k, s.cur.ref.visitId());
  if (!s.cur.ref.leaf) {
    s.block = s.cur.ref.first >> cfg_block_shift_i.read();
    setState(k, State::NodeReq);
  } else if (s.cur.ref.count > 0) {
    startRun(k, s.cur.ref.first, s.cur.ref.count);
    setState(k, State::Fetch);
  } else {
    setState(k, State::Pop);
  }
}

// NODE_REQ: the interior node's record.
void rt_bvh_model::requestNode(int k) {
  pushNode(k, slots_[size_t(k)].cur.ref.first);
  setState(k, State::WaitNode);
}

// One rt_isect result (the shell took it into the closest hit); the last one:
// FETCH ends in the next cycle.
void rt_bvh_model::absorbResult(const rt_isect_result& res) {
  if (res.res.hit) slots_[size_t(res.slot)].hitSeen = true;
  if (res.last) fin_.set(res.slot);
}

// The exit test's answer: culled (the bound lies before the candidate) -> POP, else ENTER.
void rt_bvh_model::check(int k) {
  const Slot& s = slots_[size_t(k)];
  const rt_closest_record& h = hit(k);
  const bool holds = h.settled() || fx::culledBy(h.best, s.cur.entry, s.setup);
  if (holds) {
    setState(k, State::Pop);
  } else {
    enter(k);
  }
}

// BOX: both children entered -> the nearer is the candidate, the farther
// pushed; one -> it; none -> POP.
void rt_bvh_model::takeBoxAnswer(const BoxAnswer& a) {
  Slot& s = slots_[size_t(a.slot)];
  const bool both = a.hit[0].hit && a.hit[1].hit;
  if (!a.hit[0].hit && !a.hit[1].hit) {
    setState(a.slot, State::Pop);
    return;
  }
  const size_t pick = both ? (a.hit[1].entry < a.hit[0].entry ? 1 : 0) : (a.hit[1].hit ? 1 : 0);
  if (both) {
    if (s.sp >= fx::kBvhStackDepth) fail(fmt::format("slot {}: the stack overflows ({} entries)", a.slot, fx::kBvhStackDepth));
    stacks_[size_t(a.slot)][size_t(s.sp++)] = Candidate{a.child[1 - pick], a.hit[1 - pick].entry};
  }
  candidate(a.slot, Candidate{a.child[pick], a.hit[pick].entry});
}

// POP, granted in the previous cycle: the top of the stack, or DONE.
void rt_bvh_model::pop(int k) {
  Slot& s = slots_[size_t(k)];
  if (s.sp == 0) {
    setState(k, State::Done);
    return;
  }
  candidate(k, stacks_[size_t(k)][size_t(--s.sp)]);
}

// FETCH with every result in (as the cycle began): DONE for an any-hit ray with a hit, else POP.
void rt_bvh_model::finishLeaves(const slot_mask& finishing) {
  finishing.forEach([&](int k) {
    const Slot& s = slots_[size_t(k)];
    setState(k, s.anyHit && s.hitSeen ? State::Done : State::Pop);
  });
}

// The candidate rule: CHECK if the slot is bound and the entry is not 0, else ENTER.
void rt_bvh_model::candidate(int k, const Candidate& c) {
  slots_[size_t(k)].cur = c;
  if (hit(k).wantsCheck() && c.entry != 0) {
    setState(k, State::Check);
  } else {
    enter(k);
  }
}

// ENTER, unless suspension is on and the candidate is an interior node of
// another block than the slot's with at most BVH_SUSPEND_ENTRIES entries on
// the stack: then DONE, suspended (its result carries the walk).
void rt_bvh_model::enter(int k) {
  Slot& s = slots_[size_t(k)];
  s.suspending = cfg_suspend_i.read() && !s.cur.ref.leaf && (s.cur.ref.first >> cfg_block_shift_i.read()) != s.block &&
                 s.sp <= fx::kBvhSuspendEntries;
  setState(k, s.suspending ? State::Done : State::Enter);
}

// The done slot's walk record, if it is suspended: the closest hit so far, the
// candidate, the stack (fx::bvhWalkValues' packing).
rt_bvh_model::walk_in rt_bvh_model::suspendedWalk(int k) const {
  const Slot& s = slots_[size_t(k)];
  if (!s.suspending) return {};
  fx::BvhWalk walk;
  if (hit(k).hasHit) walk.trace.hit = hit(k).best;
  walk.next = fx::BvhWalkEntry{s.cur.ref, s.cur.entry};
  for (int e = 0; e < s.sp; ++e) {
    const Candidate& c = stacks_[size_t(k)][size_t(e)];
    walk.stack.push_back(fx::BvhWalkEntry{c.ref, c.entry});
  }
  return suspendedRecord(fx::bvhWalkValues(walk));
}

// The sets a slot in state `st` belongs to, joined or left.
void rt_bvh_model::mark(int k, State st, bool join) {
  const auto put = [&](slot_mask& m) { join ? m.set(k) : m.reset(k); };
  switch (st) {
    case State::Enter: put(enter_); break;
    case State::NodeReq: put(nodeWant_); break;
    case State::Fetch:
      put(fetch_);
      if (!join) fin_.reset(k);
      break;
    case State::Pop: put(pop_); break;
    case State::Check: put(checkWant_); break;
    case State::Done: put(done_); break;
    default: break;
  }
}

// SETUP -> ENTER at the end of accept + BVH_SETUP_LATENCY: the per-ray setup,
// the root with entry 0; or a resumed walk's candidate (its box test passed,
// not culled), stack and closest hit, in the candidate's block.
void rt_bvh_model::load(int k) {
  Slot& s = slots_[size_t(k)];
  std::optional<fx::BvhWalk> walk;
  if (const auto values = resumedWalkValues()) walk = fx::bvhWalkOf(*values, uint32_t(k));
  const fx::QRay ray = loadRay(k, walk ? walk->trace.hit : std::nullopt);
  s.setup = fx::BvhRaySetup::setup(ray);
  s.anyHit = ray.anyHit;
  s.hitSeen = false;
  s.suspending = false;
  if (walk) {
    s.cur = Candidate{walk->next->ref, walk->next->entry};
    s.sp = int(walk->stack.size());
    for (size_t e = 0; e < walk->stack.size(); ++e) stacks_[size_t(k)][e] = Candidate{walk->stack[e].ref, walk->stack[e].entry};
  } else {
    std::array<uint32_t, size_t(fx::wireWords(rt_bvh_unit::CFG_W))> root{};
    fromValue<rt_bvh_unit::CFG_W>(cfg_i.read(), root);
    s.cur = Candidate{unpackRef(root.data()), 0};
    s.sp = 0;
  }
  s.block = s.cur.ref.first >> cfg_block_shift_i.read();
  setState(k, State::Enter);
}

}  // namespace lancer::sc
