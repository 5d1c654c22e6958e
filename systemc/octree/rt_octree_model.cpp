#include "octree/rt_octree_model.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "common/rt_record_bits.h"
#include "golden/isect.h"

namespace lancer::sc {

using namespace octree;

namespace {

constexpr uint32_t SLOT_MASK = (uint32_t(1) << rt_octree_unit::SLOT_W) - 1;
constexpr size_t kNodeWords = size_t(fx::wireWords(NODE_W));
constexpr size_t kGroupWords = size_t(fx::wireWords(GROUP_W));
constexpr size_t kNodeValues = fx::valueCount(fx::kOctreeNodeFields);
constexpr size_t kVisitValues = fx::valueCount(fx::kOctreeVisitFields);
constexpr size_t kResValues = fx::valueCount(fx::kOctreeResFields);
static_assert(kNodeValues == 3 && kVisitValues == 2 && kResValues == 9, "octree record layouts changed");

// ADDR_W'(value): the RTL truncates node, index-list and triangle addresses to the address width.
constexpr uint32_t addrOf(uint32_t value) {
  return MEM_ADDR_W >= 32 ? value : value & ((uint32_t(1) << MEM_ADDR_W) - 1);
}

fx::OctreeNode unpackNode(const uint32_t* wire) {  // {leaf, count, first}
  return fx::OctreeNode{getField<fx::kOctreeNodeFields, 0>(wire) != 0,
                        uint32_t(getField<fx::kOctreeNodeFields, 2>(wire)),
                        uint32_t(getField<fx::kOctreeNodeFields, 1>(wire))};
}

// isect_tri_t {prim_id, v0[3], v1[3], v2[3]} from its wire image.
fx::QTriangle unpackTriangle(const uint32_t* wire) {
  fx::QTriangle t;
  t.id = uint32_t(getField<fx::kIsectTriFields, 0>(wire));
  [&]<size_t... I>(std::index_sequence<I...>) {
    ((t.v[I / 3][I % 3] = getField<fx::kIsectTriFields, 1 + I>(wire)), ...);
  }(std::make_index_sequence<9>{});
  return t;
}
static_assert(fx::kIsectTriValues == 10, "isect_tri_t layout changed");

bool negative(const fx::OctT& t) { return t.inf < 0 || (t.inf == 0 && t.value < 0); }

bool anyNegative(const std::array<fx::OctT, 3>& t) { return negative(t[0]) || negative(t[1]) || negative(t[2]); }

constexpr fx::OctT kMinusInf{0, -1}, kPlusInf{0, 1};

}  // namespace

// ---- SlotMask -----------------------------------------------------------------

bool rt_octree_model::SlotMask::any() const {
  for (uint64_t w : w_)
    if (w) return true;
  return false;
}

int rt_octree_model::SlotMask::lowest() const {
  for (int i = 0; i < kWords; ++i)
    if (w_[size_t(i)]) return i * 64 + __builtin_ctzll(w_[size_t(i)]);
  return -1;
}

int rt_octree_model::SlotMask::lowestBelow(int limit) const {
  const int k = lowest();
  return k >= 0 && k < limit ? k : -1;
}

int rt_octree_model::SlotMask::pickFrom(int from) const {
  const int first = from >> 6;
  const uint64_t upper = w_[size_t(first)] & (~uint64_t(0) << (from & 63));
  if (upper) return first * 64 + __builtin_ctzll(upper);
  for (int i = first + 1; i < kWords; ++i)
    if (w_[size_t(i)]) return i * 64 + __builtin_ctzll(w_[size_t(i)]);
  return lowest();  // wraps around: every member lies below `from`, or there is none
}

rt_octree_model::SlotMask rt_octree_model::SlotMask::operator|(const SlotMask& o) const {
  SlotMask r;
  for (int i = 0; i < kWords; ++i) r.w_[size_t(i)] = w_[size_t(i)] | o.w_[size_t(i)];
  return r;
}

// ---- The module -----------------------------------------------------------------

rt_octree_model::rt_octree_model(sc_core::sc_module_name name)
    : rt_trav_shell<rt_octree_unit>(name) {
  reset();

  SC_METHOD(seq);
  sensitive << clk_i.pos() << rst_ni.neg();
  dont_initialize();

  SC_METHOD(comb);
  sensitive << tri_rsp_valid_i;
}

void rt_octree_model::fail(const std::string& what) const {
  SC_REPORT_ERROR(name(), what.c_str());
  throw std::runtime_error(what);  // not reached with SC_THROW
}

void rt_octree_model::reset() {
  for (Slot& s : slots_) s.state = State::Free;
  free_.clear();
  enter_.clear();
  nodeWant_.clear();
  idxWant_.clear();
  checkWant_.clear();
  advWant_.clear();
  done_.clear();
  self_.clear();
  for (int k = 0; k < N; ++k) free_.set(k);
  q_.clear();
  visitArb_ = nodeArb_ = idxArb_ = checkArb_ = doneArb_ = RoundRobin{};
  advArb_.fill(RoundRobin{});
  for (IsectStage& st : isect_) st.valid = false;
  isectPos_ = 0;
  nodeHead_ = idxHead_ = triHead_ = visitHead_ = resHead_ = true;
}

// The state register with the request vectors and the self-acting set derived from it.
void rt_octree_model::setState(int k, State next) {
  Slot& s = slots_[size_t(k)];
  switch (s.state) {  // leave the old state's sets
    case State::Free: free_.reset(k); break;
    case State::Enter: enter_.reset(k); break;
    case State::GroupReq:
    case State::RefillReq: nodeWant_.reset(k); break;
    case State::Fetch:
      idxWant_.reset(k);
      self_.reset(k);
      break;
    case State::Check:
      checkWant_.reset(k);
      advWant_.reset(k);
      break;
    case State::Descend: self_.reset(k); break;
    case State::Next: advWant_.reset(k); break;
    case State::Done: done_.reset(k); break;
    default: break;
  }
  s.state = next;
  switch (next) {
    case State::Free: free_.set(k); break;
    case State::Enter: enter_.set(k); break;
    case State::GroupReq:
    case State::RefillReq: nodeWant_.set(k); break;
    case State::Fetch:
      if (s.issued != s.rec.count) idxWant_.set(k);
      if (s.received == s.rec.count) self_.set(k);
      break;
    case State::Check:
      if (s.hit.wantsCheck()) {
        checkWant_.set(k);
      } else {
        advWant_.set(k);
      }
      break;
    case State::Descend: self_.set(k); break;
    case State::Next: advWant_.set(k); break;
    case State::Done: done_.set(k); break;
    default: break;
  }
}

// SETUP -> ENTER | DONE at the end of accept + 2: the per-ray setup and the root test.
void rt_octree_model::load(int k, const isect_ray_t& port) {
  Slot& s = slots_[size_t(k)];
  std::array<uint32_t, fx::kIsectRayWords> wire{};
  fromPort<ISECT_RAY_W>(port, wire);
  fx::unpackRay(wire, s.ray);
  s.rayId = s.ray.id;
  s.ray.id = uint32_t(k);  // rt_isect carries the slot index in ray_id
  s.setup = fx::OctreeRaySetup::setup(s.ray);
  s.t0 = s.setup.t0;
  s.t1 = s.setup.t1;
  s.nodeId = 0;
  std::array<uint32_t, kNodeWords> root{};
  fromPort<NODE_W>(cfg_root_i.read(), root);
  s.rec = unpackNode(root.data());
  s.depth = 0;
  s.groupValid = false;
  s.nodes = s.tests = s.issued = s.received = 0;
  s.hit.start(s.ray);
  const fx::OctT enter = std::max({s.t0[0], s.t0[1], s.t0[2]});
  const fx::OctT leave = std::min({s.t1[0], s.t1[1], s.t1[2]});
  setState(k, enter < leave ? State::Enter : State::Done);
}

// ENTER on the visit grant (the visit record is pushed by the caller).
void rt_octree_model::enter(int k) {
  Slot& s = slots_[size_t(k)];
  ++s.nodes;
  if (!s.rec.leaf) {
    setState(k, State::GroupReq);
  } else if (s.rec.count > 0) {
    s.tests += s.rec.count;
    s.issued = s.received = 0;
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

void rt_octree_model::seq() {
  if (!rst_ni.read()) {
    reset();
    writeOutputs(true);
    return;
  }

  // ---- Decisions of this cycle, from the registers at its start and the inputs.
  const int usable = std::min<int>(int(cfg_slots_i.read()), N);
  const int alloc = free_.lowestBelow(usable);
  const bool rayFire = ray_valid_i.read() && alloc >= 0;

  const int visitIdx = visitArb_.pick(enter_);
  const bool visitGo = visitIdx >= 0 && !q_.visitQ.full();
  const int nodeIdx = nodeArb_.pick(nodeWant_);
  const bool nodeGo = nodeIdx >= 0 && !q_.nodeQ.full();
  const int idxIdx = idxArb_.pick(idxWant_);
  const bool idxGo = idxIdx >= 0 && !q_.idxQ.full() && q_.credits != 0;
  const int checkIdx = checkArb_.pick(checkWant_);
  const int doneIdx = doneArb_.pick(done_);
  const bool doneGo = doneIdx >= 0 && !q_.resQ.full();
  const bool idxBufPop = !q_.idxBuf.empty() && !q_.triQ.full();
  const SlotMask self = self_;
  std::array<int, ADV_LANES> advIdx{};  // each lane's slot, or -1
  SlotMask advLeft = advWant_;
  for (int l = 0; l < ADV_LANES; ++l) {
    advIdx[size_t(l)] = advArb_[size_t(l)].pick(advLeft);
    if (advIdx[size_t(l)] >= 0) advLeft.reset(advIdx[size_t(l)]);
  }
  const bool setupLoad = q_.setup.s2.valid;
  const int setupSlot = q_.setup.s2.slot;

  // Memory responses (the RTL's assertions on the response tags and the index buffer).
  const bool nodeRsp = node_rsp_valid_i.read();
  int nodeSlot = -1;
  if (nodeRsp) {
    nodeSlot = int(uint32_t(node_rsp_tag_i.read()) & SLOT_MASK);
    const State st = nodeSlot < N ? slots_[size_t(nodeSlot)].state : State::Free;
    if (st != State::WaitGroup && st != State::WaitRefill) {
      fail(fmt::format("node response for slot {}, which does not wait for one", nodeSlot));
    }
  }
  const bool triRsp = tri_rsp_valid_i.read();
  int triSlot = -1;
  if (triRsp) {
    triSlot = int(uint32_t(tri_rsp_tag_i.read()) & SLOT_MASK);
    if (triSlot >= N || slots_[size_t(triSlot)].state != State::Fetch) {
      fail(fmt::format("triangle response for slot {}, which is not fetching", triSlot));
    }
  }
  const bool idxRsp = idx_rsp_valid_i.read();
  if (idxRsp && q_.idxBuf.full()) fail("index response with the index buffer full (credit error)");

  // u_isect: the result leaving the last stage in this cycle, and the pair entering.
  IsectStage& stage = isect_[isectPos_];
  const IsectStage out = stage;
  stage.valid = triRsp;
  if (triRsp) {
    std::array<uint32_t, fx::kIsectTriWords> wire{};
    fromPort<ISECT_TRI_W>(tri_rsp_data_i.read(), wire);
    stage.res = fx::intersect(slots_[size_t(triSlot)].ray, unpackTriangle(wire.data()));
  }
  isectPos_ = isectPos_ + 1 == size_t(ISECT_LATENCY) ? 0 : isectPos_ + 1;

  // ---- FIFO pops (heads of the cycle leave on ready).
  const bool nodePop = !q_.nodeQ.empty() && node_req_ready_i.read();
  const bool idxPop = !q_.idxQ.empty() && idx_req_ready_i.read();
  const bool triPop = !q_.triQ.empty() && tri_req_ready_i.read();
  const bool visitPop = !q_.visitQ.empty() && visit_ready_i.read();
  const bool resPop = !q_.resQ.empty() && res_ready_i.read();
  if (nodePop) q_.nodeQ.pop();
  if (idxPop) q_.idxQ.pop();
  if (triPop) q_.triQ.pop();
  if (visitPop) q_.visitQ.pop();
  if (resPop) q_.resQ.pop();

  // ---- The slots: at most one state-changing event per slot and cycle, each
  // reading that slot's registers as they were at the start of the cycle.
  if (visitGo) {
    const Slot& s = slots_[size_t(visitIdx)];
    visitHead_ |= q_.visitQ.empty();
    q_.visitQ.push(rt_visit_entry{s.rayId, s.nodeId});
    enter(visitIdx);
    visitArb_.ack(visitIdx);
  }
  if (nodeGo) {
    const Slot& s = slots_[size_t(nodeIdx)];
    const bool group = s.state == State::GroupReq;
    nodeHead_ |= q_.nodeQ.empty();
    q_.nodeQ.push(rt_mem_req{addrOf(group ? s.rec.first : s.stack[size_t(s.depth - 1)].first), uint32_t(nodeIdx)});
    setState(nodeIdx, group ? State::WaitGroup : State::WaitRefill);
    nodeArb_.ack(nodeIdx);
  }
  if (nodeRsp) {
    Slot& s = slots_[size_t(nodeSlot)];
    std::array<uint32_t, kGroupWords> wire{};
    fromPort<GROUP_W>(node_rsp_data_i.read(), wire);
    for (size_t i = 0; i < size_t(fx::kOctreeChildren); ++i) s.group[i] = unpackNode(wire.data() + i * kNodeWords);
    s.groupValid = true;
    if (s.state == State::WaitGroup) {
      setState(nodeSlot, State::Descend);
    } else {
      s.rec = s.group[size_t(s.stack[size_t(s.depth - 1)].child ^ s.setup.mirror)];
      setState(nodeSlot, State::Enter);
    }
  }
  if (out.valid) {  // one closest-hit update per cycle
    const int k = int(out.res.rayId & SLOT_MASK);
    Slot& s = k < N ? slots_[size_t(k)] : slots_[0];
    if (k >= N || s.state != State::Fetch || s.received == s.issued) {
      fail(fmt::format("rt_isect result for slot {}, which expects none", k));
    }
    if (s.hit.takes(out.res)) s.hit.take(out.res);
    if (++s.received == s.rec.count) self_.set(k);  // -> CHECK in the next cycle
  }
  if (idxGo) {
    Slot& s = slots_[size_t(idxIdx)];
    idxHead_ |= q_.idxQ.empty();
    q_.idxQ.push(rt_mem_req{addrOf(s.rec.first + s.issued), uint32_t(idxIdx)});
    if (++s.issued == s.rec.count) idxWant_.reset(idxIdx);
    idxArb_.ack(idxIdx);
  }
  if (checkIdx >= 0) {
    const Slot& s = slots_[size_t(checkIdx)];
    if (s.hit.settled() || fx::hitWithin(s.hit.best, s.t1, s.setup)) {
      setState(checkIdx, State::Done);
    } else {
      advance(checkIdx);  // the exit test's own lane
    }
    checkArb_.ack(checkIdx);
  }
  for (int l = 0; l < ADV_LANES; ++l) {
    const int k = advIdx[size_t(l)];
    if (k < 0) continue;
    advance(k);
    advArb_[size_t(l)].ack(k);
  }
  self.forEach([&](int k) {
    switch (slots_[size_t(k)].state) {
      case State::Descend: descend(k); break;
      case State::Fetch: setState(k, State::Check); break;  // every result is in
      default: break;
    }
  });
  if (doneGo) {
    const Slot& s = slots_[size_t(doneIdx)];
    const auto values = s.hit.resultValues(s.rayId, s.nodes, s.tests);
    std::array<uint32_t, size_t(fx::wireWords(rt_octree_unit::RESULT_W))> wire{};
    fx::packFields(fx::kOctreeResFields, values, wire);
    resHead_ |= q_.resQ.empty();
    q_.resQ.push(toPort<rt_octree_unit::RESULT_W>(wire));
    setState(doneIdx, State::Free);
    doneArb_.ack(doneIdx);
  }
  if (setupLoad) load(setupSlot, q_.setup.s2.ray);
  if (rayFire) setState(alloc, State::Setup);

  // ---- Index buffer, triangle requests, credits, setup pipeline.
  if (idxBufPop) {
    triHead_ |= q_.triQ.empty();
    q_.triQ.push(q_.idxBuf.front());
    q_.idxBuf.pop();
  }
  if (idxRsp) q_.idxBuf.push(rt_mem_req{addrOf(uint32_t(idx_rsp_data_i.read())), uint32_t(idx_rsp_tag_i.read()) & SLOT_MASK});
  if (idxGo && !idxBufPop) --q_.credits;
  if (idxBufPop && !idxGo) ++q_.credits;

  q_.setup.shift();
  if (rayFire) q_.setup.load(alloc, ray_data_i.read());

  nodeHead_ |= nodePop;
  idxHead_ |= idxPop;
  triHead_ |= triPop;
  visitHead_ |= visitPop;
  resHead_ |= resPop;
  writeOutputs(false);
}

// A flag output is written only when it changes (the signal keeps its value),
// which saves the kernel call; `all` (reset) writes every output.
void rt_octree_model::writeFlag(sc_core::sc_out<bool>& port, Flag f, bool value, bool all) {
  if (all || flags_[f] != value) {
    port.write(value);
    flags_[f] = value;
  }
}

void rt_octree_model::writeOutputs(bool all) {
  writeFlag(node_req_valid_o, NODE_VALID, !q_.nodeQ.empty(), all);
  if (!q_.nodeQ.empty() && (nodeHead_ || all)) writeRequest(q_.nodeQ, node_req_addr_o, node_req_tag_o);
  writeFlag(idx_req_valid_o, IDX_VALID, !q_.idxQ.empty(), all);
  if (!q_.idxQ.empty() && (idxHead_ || all)) writeRequest(q_.idxQ, idx_req_addr_o, idx_req_tag_o);
  writeFlag(tri_req_valid_o, TRI_VALID, !q_.triQ.empty(), all);
  if (!q_.triQ.empty() && (triHead_ || all)) writeRequest(q_.triQ, tri_req_addr_o, tri_req_tag_o);
  writeFlag(visit_valid_o, VISIT_VALID, !q_.visitQ.empty(), all);
  if (!q_.visitQ.empty() && (visitHead_ || all)) {
    std::array<uint32_t, size_t(fx::wireWords(rt_octree_unit::VISIT_W))> wire{};
    putField<fx::kOctreeVisitFields, 0>(wire.data(), q_.visitQ.front().rayId);
    putField<fx::kOctreeVisitFields, 1>(wire.data(), q_.visitQ.front().id);
    visit_data_o.write(toPort<rt_octree_unit::VISIT_W>(wire));
  }
  writeFlag(res_valid_o, RES_VALID, !q_.resQ.empty(), all);
  if (!q_.resQ.empty() && (resHead_ || all)) res_data_o.write(q_.resQ.front());
  nodeHead_ = idxHead_ = triHead_ = visitHead_ = resHead_ = false;

  const int usable = std::min<int>(int(cfg_slots_i.read()), N);
  writeFlag(ray_ready_o, RAY_READY, free_.lowestBelow(usable) >= 0, all);
  writeFlag(perf_step_ready_o, STEP_READY, enter_.any(), all);
}

void rt_octree_model::comb() {
  perf_isect_fire_o.write(tri_rsp_valid_i.read());  // rt_isect's req_ready_o is 1: it never stalls
}

}  // namespace lancer::sc
