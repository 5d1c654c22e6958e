#pragma once

// rt_trav_shell_model: the cycle model of rtl/lib/rt_trav_shell.sv, the part
// of every traversal unit that is not its walk. A unit's cycle model
// (rt_grid_model, rt_octree_model, rt_bvh_model) derives from it and holds
// only its walk and its per-ray setup; its cycle(), which the shell's clocked
// process calls once per rising edge out of reset, calls the shell's steps in
// this order:
//
//   wants      the walk's want vectors, from the registers at the start of the cycle
//   grant()    allocation (from the free slots), the five round-robin
//              arbiters (the index reads' from the index runs), FIFO room,
//              credits; the FIFO heads taken in this cycle leave
//   nodeResponse()   the node/cell response of the cycle (registered when RegRsp)
//   intersect()      u_isect: the triangle response enters with its slot's ray;
//              u_quadric: a quadric response, likewise; u_closest: the
//              result that left either CLOSEST_HIT_LATENCY cycles ago (rt_isect's
//              first, rt_quadric's waiting meanwhile) updates its slot's
//              closest hit, and counts in its run
//   (events)   the walk's slot updates; at its grants it pushes the node request
//              and the visit (push*()), starts index runs (startRun()), ends
//              a ray (finishRay(): its result, the slot free again), and loads
//              the ray leaving the setup pipeline (loadRay())
//   endCycle() the index request of the cycle's grant, the index buffer and
//              triangle requests, credits, arbiter pointers, allocation, the
//              setup pipeline, the boundary registers, the outputs
//
// As rt_trav_shell does, the shell keeps the free slots, the index runs and
// the counts of the result record (regions entered, tests issued, quadric
// tests). It models the unit as the Verilated models are built: with
// rt_quadric (Quadrics = 1), which a scene of triangles never uses.
//
// The model is plain C++ on plain values (base/rt_value.h): its ports are
// rt_values under the RTL's names, so whoever steps it sets the inputs,
// calls settle() (the combinational outputs: perf_isect_fire_o, and u_isect's
// request when it is outside) and clock() (the rising edge), and reads the
// outputs, as with a Verilated model. The run loop of the Verilated units
// does exactly that (the fast path, sw/driver/traversal_run.h);
// rt_trav_pin_model binds the same model to sc_in/sc_out for the SystemC
// kernel (the testbench's pin-level co-simulation with the Verilated RTL).
//
// u_isect (constructor argument rt_isect_impl): `model` is rt_isect's timing
// inside this model (it never stalls and its results are always taken, so it
// is an ISECT_LATENCY-deep delay line of fx::intersect); `rtl` is an rt_isect
// outside, on the `isect` ports (the Verilated rt_isect the pin-level module
// holds: the mixed system, which takes no quadric: its driver refuses them).
// u_quadric is always inside: QUADRIC_LATENCY stages of fx::intersectQuadric
// with rt_quadric's stage control (base/rt_stall_pipe.h). RegRsp is the RTL's parameter: node and triangle
// responses are used in the cycle after they arrive (rt_grid) or in it
// (rt_octree).

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "base/rt_stall_pipe.h"
#include "base/rt_value.h"
#include "common/rt_record_bits.h"
#include "common/rt_trav_ports.h"
#include "common/rt_trav_unit.h"
#include "golden/isect.h"
#include "golden/primitives.h"
#include "golden/quadric.h"
#include "golden/record_bits.h"
#include "isect/rt_isect_ports.h"
#include "isect/rt_isect_rtl.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

// A set of slots (N bits): a want vector.
template <int N>
class rt_slot_mask {
 public:
  static constexpr int kWords = (N + 63) / 64;
  void set(int k) { w_[size_t(k >> 6)] |= uint64_t(1) << (k & 63); }
  void reset(int k) { w_[size_t(k >> 6)] &= ~(uint64_t(1) << (k & 63)); }
  bool test(int k) const { return (w_[size_t(k >> 6)] >> (k & 63)) & 1; }
  bool any() const {
    for (uint64_t w : w_)
      if (w) return true;
    return false;
  }
  void clear() { w_.fill(0); }
  rt_slot_mask without(const rt_slot_mask& other) const {  // this & ~other
    rt_slot_mask out = *this;
    for (int i = 0; i < kWords; ++i) out.w_[size_t(i)] &= ~other.w_[size_t(i)];
    return out;
  }
  int lowest() const {  // -1 if empty
    for (int i = 0; i < kWords; ++i)
      if (w_[size_t(i)]) return i * 64 + __builtin_ctzll(w_[size_t(i)]);
    return -1;
  }
  int lowestBelow(int limit) const {  // the lowest member < limit, or -1
    const int k = lowest();
    return k >= 0 && k < limit ? k : -1;
  }
  // rt_rr_arb: the lowest member at or after `from`, cyclically; -1 if empty.
  int pickFrom(int from) const {
    const int first = from >> 6;
    const uint64_t upper = w_[size_t(first)] & (~uint64_t(0) << (from & 63));
    if (upper) return first * 64 + __builtin_ctzll(upper);
    for (int i = first + 1; i < kWords; ++i)
      if (w_[size_t(i)]) return i * 64 + __builtin_ctzll(w_[size_t(i)]);
    return lowest();  // wraps around: every member lies below `from`, or there is none
  }
  template <class F>
  void forEach(F f) const {
    for (int i = 0; i < kWords; ++i) {
      for (uint64_t m = w_[size_t(i)]; m != 0; m &= m - 1) f(i * 64 + __builtin_ctzll(m));
    }
  }

 private:
  std::array<uint64_t, kWords> w_{};
};

// rt_rr_arb's pointer: grants the lowest requester at or after it; moves past a used grant.
template <int N>
struct rt_rr_arb_model {
  int ptr = 0;
  int pick(const rt_slot_mask<N>& want) const { return want.pickFrom(ptr); }
  void ack(int granted) { ptr = granted + 1 == N ? 0 : granted + 1; }
};

// A fixed delay of Latency cycles, a ring: out() is what went in Latency
// cycles ago; push() puts this cycle's value in its place.
template <class T, size_t Latency>
struct rt_delay_line {
  std::array<T, Latency> items{};
  size_t pos = 0;
  const T& out() const { return items[pos]; }
  void push(const T& v) {
    items[pos] = v;
    pos = pos + 1 == Latency ? 0 : pos + 1;
  }
  void fill(const T& v) {
    items.fill(v);
    pos = 0;
  }
};

// A delay line whose entries are mostly empty (the intersection pipeline's
// results): an empty cycle copies nothing.
template <class T, size_t Latency>
struct rt_sparse_delay_line {
  std::array<T, Latency> items{};
  std::array<bool, Latency> full{};
  size_t pos = 0;
  bool outValid() const { return full[pos]; }
  const T& out() const { return items[pos]; }  // while outValid()
  void push(bool valid, const T& v) {
    full[pos] = valid;
    if (valid) items[pos] = v;
    pos = pos + 1 == Latency ? 0 : pos + 1;
  }
  void clear() {
    full.fill(false);
    pos = 0;
  }
};

// rt_fifo: Depth entries; in_ready = !full, out_valid = !empty, from the
// occupancy at the start of the cycle.
template <class T, size_t Depth>
struct rt_fifo_model {
  std::array<T, Depth> items{};
  size_t head = 0, size = 0;
  bool full() const { return size == Depth; }
  bool empty() const { return size == 0; }
  const T& front() const { return items[head]; }
  void pop() {
    head = head + 1 == Depth ? 0 : head + 1;
    --size;
  }
  void push(const T& v) {
    size_t tail = head + size;
    if (tail >= Depth) tail -= Depth;
    items[tail] = v;
    ++size;
  }
  void clear() { head = size = 0; }
};

// A memory request FIFO entry (node/cell, index, triangle ports; the index
// buffer's {primitive entry, slot}); quadric: the triangle port's read is of
// the quadric table (the entry's kind bit).
struct rt_mem_req {
  uint32_t addr = 0, slot = 0;
  bool quadric = false;
};

// A visit FIFO entry: {ray_id, element id} (a cell id, a node id).
struct rt_visit_entry {
  uint32_t rayId = 0, id = 0;
};

// The setup pipeline's valid/slot/ray registers, Stages of them (the unit's
// SETUP_LATENCY; the arithmetic happens at the slot load, after the last).
// Per cycle: shift(), then load() the ray accepted in it.
template <int Stages, class Extra>
struct rt_setup_pipe {
  static_assert(Stages >= 1);
  struct stage {
    bool valid = false;
    int slot = 0;
    value_t<ISECT_RAY_W> ray{};
    Extra extra{};  // what comes with the ray (a resumed walk)
  };
  std::array<stage, Stages> s{};

  const stage& last() const { return s[Stages - 1]; }
  void clear() {
    for (stage& st : s) st.valid = false;
  }
  void shift() {
    for (int i = Stages - 1; i > 0; --i) {
      if (s[i - 1].valid) {
        s[i].slot = s[i - 1].slot;
        s[i].ray = s[i - 1].ray;
        s[i].extra = s[i - 1].extra;
      }
      s[i].valid = s[i - 1].valid;
    }
    s[0].valid = false;
  }
  void load(int slot, const value_t<ISECT_RAY_W>& ray, const Extra& extra) {
    s[0].valid = true;
    s[0].slot = slot;
    s[0].ray = ray;
    s[0].extra = extra;
  }
};

// The suspension ports of a unit that can set a walk aside (Unit::kSuspends;
// docs/scheduling.md, "The treelet schedule"): with cfg_suspend_i, a walk
// about to enter an interior node of another block (node index >>
// cfg_block_shift_i) than its own leaves on the result port with its state
// (res_suspended_o, res_walk_o); a ray offered with ray_resume_i resumes the
// walk of ray_walk_i. A unit without them has none of these ports.
template <class Unit, bool = Unit::kSuspends>
struct rt_suspend_ports {
  struct walk_in {};  // nothing comes with a ray
};
template <class Unit>
struct rt_suspend_ports<Unit, true> {
  using walk_t = value_t<Unit::WALK_W>;
  rt_value<bool> cfg_suspend_i;
  rt_value<uint32_t> cfg_block_shift_i;
  rt_value<bool> ray_resume_i;
  rt_value<walk_t> ray_walk_i;
  rt_value<bool> res_suspended_o;
  rt_value<walk_t> res_walk_o;
  // A resumed walk on its way through the setup pipeline, and a result record's.
  struct walk_in {
    bool carried = false;  // the ray resumes this walk; the result suspends it
    walk_t walk{};
  };
};

// A slot's closest-hit record, as rt_trav_shell keeps it: the closest hit so
// far, and before the first one the segment end as a pseudo hit (the bound the
// exit test compares with; fx::walkBound). A bounded ray is exit-tested before
// its first hit; an any-hit ray with a hit is settled (the walk ends without
// the exit test's arithmetic).
struct rt_closest_record {
  bool hasHit = false;
  bool bounded = false;
  bool anyHit = false;
  fx::IsectResult best;

  void start(const fx::QRay& ray) {
    hasHit = false;
    bounded = ray.bounded();
    anyHit = ray.anyHit;
    best = fx::segmentEndBound(ray);
  }
  // rt_closest_hit: does the result replace the record?
  bool takes(const fx::IsectResult& res) const { return res.hit && (!hasHit || fx::closerResult(res, best)); }
  void take(const fx::IsectResult& res) {
    hasHit = true;
    best = res;
  }
  // A resumed walk's: the closest hit it carries, or none yet.
  void resume(const fx::QRay& ray, const std::optional<fx::IsectResult>& hit) {
    start(ray);
    if (hit) take(*hit);
  }
  bool wantsCheck() const { return hasHit || bounded; }
  bool settled() const { return anyHit && hasHit; }
  // The unit's result record: {ray id, elements visited, tests, quadric
  // tests, hit, the hit's fields (zero without one)}.
  std::array<fx::u128, 10> resultValues(uint32_t rayId, uint32_t visited, uint64_t tests,
                                        uint64_t quadricTests) const {
    const fx::IsectResult hit = hasHit ? best : fx::IsectResult{};
    return {rayId, visited, tests, quadricTests, hasHit ? 1u : 0u, hit.primId, hit.tNum, hit.det, hit.uNum, hit.vNum};
  }
};

// The walk's want vectors (rt_trav_shell's want_node, want_visit,
// want_check, want_done, fetching).
template <int N>
struct rt_trav_wants {
  rt_slot_mask<N> node, visit, check, done;
  rt_slot_mask<N> expect;  // slots that expect triangles and results (FETCH)
};

// The grants of a cycle: the granted slot of each arbiter whose grant goes, or
// -1; alloc: the slot that takes the ray offered in this cycle, or -1; check:
// the slot whose exit test answers in this cycle (granted EXIT_TEST_LATENCY
// cycles before), or -1.
struct rt_trav_grants {
  int alloc = -1, node = -1, visit = -1, idx = -1, check = -1, done = -1;
};

// The intersection result absorbed in this cycle; last: it completes its
// slot's index run.
struct rt_isect_result {
  bool valid = false;
  int slot = -1;
  bool last = false;
  fx::IsectResult res;
};

// A slot's index run (a leaf's or a cell's triangles): where its index list
// starts, how many it lists, the index reads issued and the results in
// (rt_trav_shell's rt_idx_count).
struct rt_index_run {
  uint32_t first = 0, count = 0, issued = 0, received = 0;
};

// isect_tri_t {prim_id, v0[3], v1[3], v2[3]} from its wire image.
inline fx::QTriangle unpackTriangle(const uint32_t* wire) {
  static_assert(fx::kIsectTriValues == 10, "isect_tri_t layout changed");
  fx::QTriangle t;
  t.id = uint32_t(getField<fx::kIsectTriFields, 0>(wire));
  [&]<size_t... I>(std::index_sequence<I...>) {
    ((t.v[I / 3][I % 3] = getField<fx::kIsectTriFields, 1 + I>(wire)), ...);
  }(std::make_index_sequence<9>{});
  return t;
}

template <class Unit, bool RegRsp>
class rt_trav_shell_model : public rt_trav_unit_ports<Unit, rt_value, rt_value, value_t>,
                            public rt_suspend_ports<Unit> {
 public:
  using walk_in = typename rt_suspend_ports<Unit>::walk_in;
  static constexpr int N = Unit::RAYS_IN_FLIGHT;
  static constexpr bool kRegisteredResponses = RegRsp;
  using slot_mask = rt_slot_mask<N>;
  using wants_t = rt_trav_wants<N>;
  using unit_t = Unit;
  using node_data_t = value_t<Unit::NODE_DATA_W>;
  using res_t = value_t<Unit::RESULT_W>;

  // The unit's configuration port (its RTL name: Unit::kNames.cfgPort).
  rt_value<value_t<Unit::CFG_W>> cfg_i;
  // u_isect's ports when it is outside (rt_isect_impl::rtl); unused otherwise.
  rt_isect_ports<rt_value, rt_value, value_t> isect;

  explicit rt_trav_shell_model(rt_isect_impl isect) : outsideIsect_(isect == rt_isect_impl::rtl) {}
  virtual ~rt_trav_shell_model() = default;
  rt_trav_shell_model(const rt_trav_shell_model&) = delete;
  rt_trav_shell_model& operator=(const rt_trav_shell_model&) = delete;

  bool outsideIsect() const { return outsideIsect_; }

  // rst_ni low: every register; every output written.
  void reset() {
    resetWalk();
    resetShell();
  }
  // The combinational outputs from the inputs and the registers:
  // perf_isect_fire_o, and u_isect's request when it is outside.
  void settle() {
    const tri_in in = triInput();
    if (outsideIsect_) {
      if (in.valid && in.slot < N) {
        std::array<uint32_t, fx::kIsectRayWords> wire{};
        fx::packWire(ray_[size_t(in.slot)], wire);
        isect.req_ray_i = toValue<ISECT_RAY_W>(wire);
        isect.req_tri_i = *in.data;
      }
      isect.req_valid_i = in.valid;
    }
    this->perf_isect_fire_o = (in.valid && (!outsideIsect_ || isect.req_ready_o)) || quadricInput().valid;
  }
  // The rising edge at the end of the cycle (rst_ni high), from the inputs as
  // they stand. (The combinational outputs follow the next settle().)
  void clock() { cycle(); }

 protected:
  static constexpr uint32_t SLOT_MASK = (uint32_t(1) << Unit::SLOT_W) - 1;

  // ADDR_W'(value): the RTL truncates addresses to the address width.
  static constexpr uint32_t addrOf(uint32_t value) {
    return MEM_ADDR_W >= 32 ? value : value & ((uint32_t(1) << MEM_ADDR_W) - 1);
  }

  // A node/cell response of this cycle; data valid while `valid`.
  struct node_rsp {
    bool valid = false;
    int slot = -1;
    const node_data_t* data = nullptr;
  };

  // The unit's cycle model provides these two: its cycle, once per rising
  // edge out of reset (the shell's steps and its walk's, in the order above),
  // and its walk's registers at reset (the shell resets its own after them).
  virtual void cycle() = 0;
  virtual void resetWalk() = 0;

  // Reset: every register, and every output written.
  void resetShell() {
    free_.clear();
    for (int k = 0; k < N; ++k) free_.set(k);
    idxWant_.clear();
    run_.fill({});
    q_setup_.clear();
    nodeQ_.clear();
    idxQ_.clear();
    triQ_.clear();
    idxBuf_.clear();
    visitQ_.clear();
    resQ_.clear();
    credits_ = IDX_BUF_DEPTH;
    nodeArb_ = visitArb_ = idxArb_ = checkArb_ = doneArb_ = rt_rr_arb_model<N>{};
    checkLine_.fill(-1);
    checkGrant_ = -1;
    nodeRsp_.valid = triRsp_.valid = quadricRsp_.valid = false;
    pipe_.clear();
    quadricPipe_.reset();
    closest_.clear();
    isect.res_ready_i = true;  // rt_trav_shell takes every rt_isect result
    writeOutputs(false);
    settle();
  }

  // Allocation, the arbiters' grants that go (FIFO room, a credit), the checks
  // on the index response; then the FIFO heads taken in this cycle leave.
  rt_trav_grants grant(const wants_t& w) {
    rt_trav_grants g;
    const int usable = std::min<int>(int(this->cfg_slots_i.read()), N);
    if (this->ray_valid_i.read()) g.alloc = free_.lowestBelow(usable);
    g.node = goes(nodeArb_.pick(w.node), !nodeQ_.full());
    g.visit = goes(visitArb_.pick(w.visit), !visitQ_.full());
    g.idx = goes(idxArb_.pick(idxWant_), !idxQ_.full() && credits_ != 0);
    // Exit tests (rt_trav_shell, rt_exit_test): this cycle's answer leaves the
    // delay line; a slot not under test may start one.
    g.check = checkLine_.out();
    checkGrant_ = checkArb_.pick(w.check.without(underTest()));
    g.done = goes(doneArb_.pick(w.done), !resQ_.full());
    idxBufPop_ = !idxBuf_.empty() && !triQ_.full();
    if (this->idx_rsp_valid_i.read() && idxBuf_.full()) fail("index response with the index buffer full (credit error)");

    popOnReady(nodeQ_, this->node_req_ready_i);
    popOnReady(idxQ_, this->idx_req_ready_i);
    popOnReady(triQ_, this->tri_req_ready_i);
    visitHead_ |= popOnReady(visitQ_, this->visit_ready_i);
    resHead_ |= popOnReady(resQ_, this->res_ready_i);
    return g;
  }

  node_rsp nodeResponse() const {
    if constexpr (RegRsp) {
      return {nodeRsp_.valid, int(nodeRsp_.tag & SLOT_MASK), &nodeRsp_.data};
    } else {
      const bool valid = this->node_rsp_valid_i.read();
      return {valid, valid ? int(uint32_t(this->node_rsp_tag_i.read()) & SLOT_MASK) : -1,
              &this->node_rsp_data_i.read()};
    }
  }

  // u_isect and u_quadric in this cycle: the triangle or quadric response
  // enters its pipeline with its slot's ray; the result leaving rt_isect, else
  // the one leaving rt_quadric (which holds it otherwise), enters u_closest
  // (rt_closest_hit), and the one that left CLOSEST_HIT_LATENCY cycles ago
  // updates its slot's closest hit and is returned: the walk sees a result
  // that many cycles after its pipeline (the RTL writes through and forwards
  // between back-to-back results of a slot, which is this sequential update).
  rt_isect_result intersect(const slot_mask& expect) {
    const tri_in in = triInput();
    if (in.valid && (in.slot >= N || !expect.test(in.slot))) {
      fail(fmt::format("triangle response for slot {}, which is not fetching", in.slot));
    }
    const quadric_in quadricIn = quadricInput();
    if (quadricIn.valid) {
      if (quadricIn.slot >= N || !expect.test(quadricIn.slot)) {
        fail(fmt::format("quadric response for slot {}, which is not fetching", quadricIn.slot));
      }
      if (in.valid) fail("a triangle and a quadric response in one cycle (one primitive port)");
      if (outsideIsect_) fail("a quadric response in the mixed system (its rt_isect is outside; no rt_quadric)");
      ++quadricTests_[size_t(quadricIn.slot)];
    }
    rt_isect_result leaving;
    if (outsideIsect_) {
      leaving.valid = isect.res_valid_o;
      if (leaving.valid) {
        std::array<uint32_t, fx::kIsectResWords> wire{};
        fromValue<ISECT_RES_W>(isect.res_data_o, wire);
        fx::unpackResult(wire, leaving.res);
      }
    } else {
      leaving.valid = pipe_.outValid();
      if (leaving.valid) leaving.res = pipe_.out();
      fx::IsectResult entering;
      if (in.valid) {
        std::array<uint32_t, fx::kIsectTriWords> wire{};
        fromValue<ISECT_TRI_W>(*in.data, wire);
        entering = fx::intersect(ray_[size_t(in.slot)], unpackTriangle(wire.data()));
      }
      pipe_.push(in.valid, entering);
    }
    // rt_quadric: its result leaves when rt_isect's does not (res_ready_i).
    const bool quadricTaken = !leaving.valid;
    if (quadricIn.valid && !quadricPipe_.ready(quadricTaken)) fail("rt_quadric not ready for a quadric response");
    if (!leaving.valid && quadricPipe_.outValid()) {
      leaving.valid = true;
      leaving.res = quadricPipe_.out();
    }
    quadricPipe_.clock(quadricTaken, quadricIn.valid, [&](fx::IsectResult& out) {
      std::array<uint32_t, size_t(fx::wireWords(ISECT_QUADRIC_W))> wire{};
      fromValue<ISECT_QUADRIC_W>(*quadricIn.data, wire);
      out = fx::intersectQuadric(ray_[size_t(quadricIn.slot)], fx::unpackQuadric(wire));
    });
    if (leaving.valid) {
      leaving.slot = int(leaving.res.rayId & SLOT_MASK);
      if (leaving.slot >= N || !expect.test(leaving.slot)) {
        fail(fmt::format("rt_isect result for slot {}, which expects none", leaving.slot));
      }
    }
    rt_isect_result out;
    if (closest_.outValid()) out = closest_.out();
    closest_.push(leaving.valid, leaving);
    if (out.valid) {
      rt_closest_record& hit = hit_[size_t(out.slot)];
      if (hit.takes(out.res)) hit.take(out.res);
      rt_index_run& run = run_[size_t(out.slot)];
      if (run.received == run.issued) fail(fmt::format("rt_isect result for slot {}, which expects none", out.slot));
      out.last = ++run.received == run.count;
    }
    return out;
  }

  // The slot whose ray leaves the setup pipeline in this cycle, or -1.
  int loadSlot() const { return q_setup_.last().valid ? q_setup_.last().slot : -1; }

  // The slot's records from that ray (rt_trav_shell's init): its id, its ray
  // for u_isect (with the slot index as id, returned), its closest hit (a
  // resumed walk's: `hit`, the one its record carries).
  fx::QRay loadRay(int k, const std::optional<fx::IsectResult>& hit = std::nullopt) {
    fx::QRay ray;
    std::array<uint32_t, fx::kIsectRayWords> wire{};
    fromValue<ISECT_RAY_W>(q_setup_.last().ray, wire);
    fx::unpackRay(wire, ray);
    rayId_[size_t(k)] = ray.id;
    ray.id = uint32_t(k);
    ray_[size_t(k)] = ray;
    hit_[size_t(k)].resume(ray, hit);
    visits_[size_t(k)] = 0;
    tests_[size_t(k)] = 0;
    quadricTests_[size_t(k)] = 0;
    return ray;
  }

  // Slot k starts an index run of `count` triangles listed from `first` (a
  // leaf's, a cell's): the shell counts them as tests and asks for their
  // index reads; intersect() marks the result that completes the run.
  void startRun(int k, uint32_t first, uint32_t count) {
    run_[size_t(k)] = rt_index_run{first, count, 0, 0};
    tests_[size_t(k)] += count;
    if (count != 0) idxWant_.set(k);
  }

  // The records pushed at the grants of this cycle (each from its slot's
  // registers at the start of the cycle).
  void pushNode(int k, uint32_t addr) { nodeQ_.push(rt_mem_req{addrOf(addr), uint32_t(k)}); }
  void pushVisit(int k, uint32_t id) {
    push(visitQ_, visitHead_, rt_visit_entry{rayId_[size_t(k)], id});
    ++visits_[size_t(k)];
  }
  // The resumed walk leaving the setup pipeline with its ray (loadSlot()), if it is one.
  const walk_in* resumedWalk() const {
    if constexpr (Unit::kSuspends) {
      return q_setup_.last().extra.carried ? &q_setup_.last().extra : nullptr;
    } else {
      return nullptr;
    }
  }

  // The resumed walk's record as field values (the descriptor's
  // kWalkFieldList, as fx::<unit>WalkOf reads them), if the ray leaving the
  // setup pipeline resumes one.
  template <class U = Unit>
    requires U::kSuspends
  auto resumedWalkValues() const {
    using values = decltype(fx::wire_bits::unpackFixed<U::descriptor::kWalkFieldList>({}));
    const walk_in* resumed = resumedWalk();
    if (resumed == nullptr) return std::optional<values>{};
    std::array<uint32_t, size_t(fx::wireWords(U::WALK_W))> wire{};
    fromValue<U::WALK_W>(resumed->walk, wire);
    return std::optional<values>{fx::wire_bits::unpackFixed<U::descriptor::kWalkFieldList>(wire)};
  }

  // A suspended walk's record for the result port, from its field values (as
  // fx::<unit>WalkValues gives them).
  template <class Values, class U = Unit>
    requires U::kSuspends
  static walk_in suspendedRecord(const Values& values) {
    std::array<uint32_t, size_t(fx::wireWords(U::WALK_W))> wire{};
    fx::wire_bits::packFixed<U::descriptor::kWalkFieldList>(values, wire);
    return walk_in{true, toValue<U::WALK_W>(wire)};
  }

  // The done grant: the ray's result record (its counts since it entered the
  // slot), with the walk's record when the walk is suspended; the slot is free again.
  void finishRay(int k, const walk_in& suspended = {}) {
    const auto values =
        hit_[size_t(k)].resultValues(rayId_[size_t(k)], visits_[size_t(k)], tests_[size_t(k)], quadricTests_[size_t(k)]);
    std::array<uint32_t, size_t(fx::wireWords(Unit::RESULT_W))> wire;
    fx::wire_bits::packFixed<Unit::descriptor::kResFieldList>(values, wire);
    push(resQ_, resHead_, res_entry{toValue<Unit::RESULT_W>(wire), suspended});
    free_.set(k);
  }

  // The rest of the cycle: the granted index read, index buffer -> triangle
  // requests, credits, arbiter pointers, allocation, setup pipeline, boundary
  // registers; then the outputs, with whether a visit is wanted
  // (perf_step_ready_o) from the registers at the end of the cycle.
  void endCycle(const rt_trav_grants& g, bool stepReady) {
    if (g.idx >= 0) {
      rt_index_run& run = run_[size_t(g.idx)];
      idxQ_.push(rt_mem_req{addrOf(run.first + run.issued), uint32_t(g.idx)});
      if (++run.issued == run.count) idxWant_.reset(g.idx);
    }
    if (idxBufPop_) {
      triQ_.push(idxBuf_.front());
      idxBuf_.pop();
    }
    if (this->idx_rsp_valid_i.read()) {
      const uint32_t entry = uint32_t(this->idx_rsp_data_i.read());
      idxBuf_.push({addrOf(entry), uint32_t(this->idx_rsp_tag_i.read()) & SLOT_MASK, fx::isQuadricEntry(entry)});
    }
    if (g.idx >= 0 && !idxBufPop_) --credits_;
    if (idxBufPop_ && g.idx < 0) ++credits_;

    ack(nodeArb_, g.node);
    ack(visitArb_, g.visit);
    ack(idxArb_, g.idx);
    ack(checkArb_, checkGrant_);
    checkLine_.push(checkGrant_);
    ack(doneArb_, g.done);

    q_setup_.shift();
    if (g.alloc >= 0) {
      free_.reset(g.alloc);
      walk_in resumed;
      if constexpr (Unit::kSuspends) {
        resumed.carried = this->ray_resume_i.read();
        if (resumed.carried) resumed.walk = this->ray_walk_i.read();
      }
      q_setup_.load(g.alloc, this->ray_data_i.read(), resumed);
    }

    if constexpr (RegRsp) {
      registerResponse(nodeRsp_, this->node_rsp_valid_i, this->node_rsp_tag_i, this->node_rsp_data_i);
      registerResponse(triRsp_, this->tri_rsp_valid_i, this->tri_rsp_tag_i, this->tri_rsp_data_i);
      registerResponse(quadricRsp_, this->quadric_rsp_valid_i, this->quadric_rsp_tag_i, this->quadric_rsp_data_i);
    }
    writeOutputs(stepReady);
  }

  const rt_closest_record& hit(int k) const { return hit_[size_t(k)]; }

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(fmt::format("{}: {}", Unit::kNames.module, what));
  }

 private:
  template <class Data>
  struct boundary_reg {
    bool valid = false;
    uint32_t tag = 0;
    Data data{};
  };
  // The triangle response entering u_isect in this cycle, or the quadric
  // response entering u_quadric.
  template <int W>
  struct response_in {
    bool valid = false;
    int slot = -1;
    const value_t<W>* data = nullptr;
  };
  using tri_in = response_in<ISECT_TRI_W>;
  using quadric_in = response_in<ISECT_QUADRIC_W>;

  static int goes(int granted, bool room) { return room ? granted : -1; }
  static void ack(rt_rr_arb_model<N>& arb, int granted) {
    if (granted >= 0) arb.ack(granted);
  }
  template <class Fifo>
  static bool popOnReady(Fifo& q, const rt_value<bool>& ready) {
    const bool pop = !q.empty() && ready.read();
    if (pop) q.pop();
    return pop;
  }
  template <class Fifo, class T>
  static void push(Fifo& q, bool& headChanged, const T& v) {
    headChanged |= q.empty();
    q.push(v);
  }
  template <class Reg, class Tag, class Data>
  static void registerResponse(Reg& r, const rt_value<bool>& valid, const Tag& tag, const Data& data) {
    r.valid = valid.read();
    if (r.valid) {
      r.tag = uint32_t(tag.read());
      r.data = data.read();
    }
  }

  // A response as its pipeline takes it: registered at the boundary (RegRsp),
  // or from the ports.
  template <int W, class Reg, class Valid, class Tag, class Data>
  static response_in<W> responseInput(const Reg& reg, const Valid& valid, const Tag& tag, const Data& data) {
    if constexpr (RegRsp) {
      return {reg.valid, int(reg.tag & SLOT_MASK), &reg.data};
    } else {
      const bool v = valid.read();
      return {v, v ? int(uint32_t(tag.read()) & SLOT_MASK) : -1, &data.read()};
    }
  }
  tri_in triInput() const {
    return responseInput<ISECT_TRI_W>(triRsp_, this->tri_rsp_valid_i, this->tri_rsp_tag_i, this->tri_rsp_data_i);
  }
  quadric_in quadricInput() const {
    return responseInput<ISECT_QUADRIC_W>(quadricRsp_, this->quadric_rsp_valid_i, this->quadric_rsp_tag_i,
                                          this->quadric_rsp_data_i);
  }

  // The slots whose exit test is in flight (rt_trav_shell's testing_q),
  // the one answering in this cycle included: they ask for no other.
  slot_mask underTest() const {
    slot_mask m;
    for (const int k : checkLine_.items) {
      if (k >= 0) m.set(k);
    }
    return m;
  }

  template <class Fifo, class Valid, class Addr, class Tag>
  static void writeRequest(const Fifo& q, Valid& valid, Addr& addr, Tag& tag) {
    valid = !q.empty();
    if (!q.empty()) {
      addr = q.front().addr;
      tag = q.front().slot;
    }
  }

  // The outputs from the registers at the end of the cycle; a record output's
  // data only when its FIFO's head changed (ports hold their value).
  void writeOutputs(bool stepReady) {
    writeRequest(nodeQ_, this->node_req_valid_o, this->node_req_addr_o, this->node_req_tag_o);
    writeRequest(idxQ_, this->idx_req_valid_o, this->idx_req_addr_o, this->idx_req_tag_o);
    writeRequest(triQ_, this->tri_req_valid_o, this->tri_req_addr_o, this->tri_req_tag_o);
    if (!triQ_.empty()) this->tri_req_quadric_o = triQ_.front().quadric;
    this->visit_valid_o = !visitQ_.empty();
    if (!visitQ_.empty() && visitHead_) {
      std::array<uint32_t, size_t(fx::wireWords(Unit::VISIT_W))> wire{};
      putField<Unit::kVisitFields, 0>(wire.data(), visitQ_.front().rayId);
      putField<Unit::kVisitFields, 1>(wire.data(), visitQ_.front().id);
      this->visit_data_o = toValue<Unit::VISIT_W>(wire);
    }
    this->res_valid_o = !resQ_.empty();
    if (!resQ_.empty() && resHead_) {
      this->res_data_o = resQ_.front().res;
      if constexpr (Unit::kSuspends) {
        this->res_suspended_o = resQ_.front().walk.carried;
        this->res_walk_o = resQ_.front().walk.walk;
      }
    }
    visitHead_ = resHead_ = false;

    const int usable = std::min<int>(int(this->cfg_slots_i.read()), N);
    this->ray_ready_o = free_.lowestBelow(usable) >= 0;
    this->perf_step_ready_o = stepReady;
  }

  const bool outsideIsect_;

  // Per slot: the ray's own id, its ray for u_isect (id = the slot index), its
  // closest hit, its index run, the counts of its result record.
  std::array<uint32_t, N> rayId_{};
  std::array<fx::QRay, N> ray_{};
  std::array<rt_closest_record, N> hit_{};
  std::array<rt_index_run, N> run_{};
  std::array<uint32_t, N> visits_{};
  std::array<uint64_t, N> tests_{};
  std::array<uint64_t, N> quadricTests_{};
  slot_mask free_;     // FREE: allocation takes the lowest usable one
  slot_mask idxWant_;  // index runs with reads left to issue

  // A result FIFO entry: the record, and a suspended walk's (walk.carried).
  struct res_entry {
    res_t res{};
    walk_in walk{};
  };
  rt_setup_pipe<Unit::SETUP_LATENCY, walk_in> q_setup_;
  rt_fifo_model<rt_mem_req, MEMREQ_FIFO_DEPTH> nodeQ_, idxQ_, triQ_;
  rt_fifo_model<rt_mem_req, IDX_BUF_DEPTH> idxBuf_;  // {triangle id, slot}
  rt_fifo_model<rt_visit_entry, VISIT_FIFO_DEPTH> visitQ_;
  rt_fifo_model<res_entry, RES_FIFO_DEPTH> resQ_;
  int credits_ = IDX_BUF_DEPTH;  // index buffer entries not yet claimed by a request
  bool idxBufPop_ = false;       // this cycle's
  rt_rr_arb_model<N> nodeArb_, visitArb_, idxArb_, checkArb_, doneArb_;
  // The exit tests in flight: the slots granted in the last EXIT_TEST_LATENCY
  // cycles (-1: none); out() answers in this cycle.
  rt_delay_line<int, fx::kExitTestLatency> checkLine_;
  int checkGrant_ = -1;  // this cycle's grant
  boundary_reg<node_data_t> nodeRsp_;  // RegRsp only
  boundary_reg<value_t<ISECT_TRI_W>> triRsp_;
  boundary_reg<value_t<ISECT_QUADRIC_W>> quadricRsp_;

  rt_sparse_delay_line<fx::IsectResult, ISECT_LATENCY> pipe_;  // u_isect inside (rt_isect_impl::model)
  rt_stall_pipe<QUADRIC_LATENCY, fx::IsectResult> quadricPipe_;  // u_quadric
  rt_sparse_delay_line<rt_isect_result, fx::kClosestHitLatency> closest_;  // u_closest's stages R to Y

  // Whether a record FIFO's head changed since its data output was written.
  bool visitHead_ = true, resHead_ = true;
};

}  // namespace lancer::sc
