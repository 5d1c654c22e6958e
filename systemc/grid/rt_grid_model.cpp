#include "grid/rt_grid_model.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "golden/isect.h"
#include "isect/rt_isect_model.h"

#if LANCER_SC_HAVE_RTL
#include "Vrt_isect_sc.h"
#endif

namespace lancer::sc {

namespace {

constexpr int N = RAYS_IN_FLIGHT;
constexpr uint32_t SLOT_MASK = (uint32_t(1) << SLOT_W) - 1;

// ADDR_W'(value): the RTL truncates cell ids, index positions and triangle ids to the address width.
constexpr uint32_t addrOf(uint32_t value) {
  return MEM_ADDR_W >= 32 ? value : value & ((uint32_t(1) << MEM_ADDR_W) - 1);
}

// u_isect's ports, connected as rt_grid connects rt_isect.
template <class Isect, class Sig>
void bindIsect(Isect& m, Sig& clk, Sig& rst, sc_core::sc_signal<bool>& reqValid, sc_core::sc_signal<bool>& reqReady,
               sc_core::sc_signal<isect_ray_t>& ray, sc_core::sc_signal<isect_tri_t>& tri,
               sc_core::sc_signal<bool>& resValid, sc_core::sc_signal<bool>& resReady,
               sc_core::sc_signal<isect_res_t>& res) {
  m.clk_i(clk);
  m.rst_ni(rst);
  m.req_valid_i(reqValid);
  m.req_ready_o(reqReady);
  m.req_ray_i(ray);
  m.req_tri_i(tri);
  m.res_valid_o(resValid);
  m.res_ready_i(resReady);
  m.res_data_o(res);
}

}  // namespace

rt_grid_model::rt_grid_model(sc_core::sc_module_name name, rt_isect_impl isect)
    : sc_core::sc_module(name),
      clk_i("clk_i"),
      rst_ni("rst_ni"),
      cfg_res_i("cfg_res_i"),
      cfg_slots_i("cfg_slots_i"),
      ray_valid_i("ray_valid_i"),
      ray_ready_o("ray_ready_o"),
      ray_data_i("ray_data_i"),
      res_valid_o("res_valid_o"),
      res_ready_i("res_ready_i"),
      res_data_o("res_data_o"),
      visit_valid_o("visit_valid_o"),
      visit_ready_i("visit_ready_i"),
      visit_data_o("visit_data_o"),
      cell_req_valid_o("cell_req_valid_o"),
      cell_req_ready_i("cell_req_ready_i"),
      cell_req_addr_o("cell_req_addr_o"),
      cell_req_tag_o("cell_req_tag_o"),
      cell_rsp_valid_i("cell_rsp_valid_i"),
      cell_rsp_data_i("cell_rsp_data_i"),
      cell_rsp_tag_i("cell_rsp_tag_i"),
      idx_req_valid_o("idx_req_valid_o"),
      idx_req_ready_i("idx_req_ready_i"),
      idx_req_addr_o("idx_req_addr_o"),
      idx_req_tag_o("idx_req_tag_o"),
      idx_rsp_valid_i("idx_rsp_valid_i"),
      idx_rsp_data_i("idx_rsp_data_i"),
      idx_rsp_tag_i("idx_rsp_tag_i"),
      tri_req_valid_o("tri_req_valid_o"),
      tri_req_ready_i("tri_req_ready_i"),
      tri_req_addr_o("tri_req_addr_o"),
      tri_req_tag_o("tri_req_tag_o"),
      tri_rsp_valid_i("tri_rsp_valid_i"),
      tri_rsp_data_i("tri_rsp_data_i"),
      tri_rsp_tag_i("tri_rsp_tag_i"),
      perf_isect_fire_o("perf_isect_fire_o"),
      slots_(size_t(N)) {
  if (isect == rt_isect_impl::model) {
    auto m = std::make_unique<rt_isect_model>("u_isect");
    bindIsect(*m, clk_i, rst_ni, isect_req_valid, isect_req_ready, isect_ray, isect_tri, isect_res_valid,
              isect_res_ready, isect_res);
    u_isect = std::move(m);
  } else {
#if LANCER_SC_HAVE_RTL
    auto m = std::make_unique<Vrt_isect_sc>("u_isect");
    bindIsect(*m, clk_i, rst_ni, isect_req_valid, isect_req_ready, isect_ray, isect_tri, isect_res_valid,
              isect_res_ready, isect_res);
    u_isect = std::move(m);
#else
    throw std::runtime_error("rt_grid_model: the Verilated rt_isect is not part of this build");
#endif
  }

  SC_METHOD(seq);
  sensitive << clk_i.pos() << rst_ni.neg();
  dont_initialize();

  SC_METHOD(comb);
  sensitive << cfg_slots_i << tri_rsp_valid_i << tri_rsp_tag_i << tri_rsp_data_i << isect_req_ready
            << state_changed_;
}

rt_grid_model::~rt_grid_model() = default;

void rt_grid_model::fail(const std::string& what) const {
  SC_REPORT_ERROR(name(), what.c_str());
  throw std::runtime_error(what);  // not reached with SC_THROW
}

fx::GridRes rt_grid_model::resolution() const {
  const uint32_t cfg = uint32_t(cfg_res_i.read());
  constexpr uint32_t mask = (uint32_t(1) << GRID_RESOLUTION_W) - 1;
  return {int(cfg & mask), int((cfg >> GRID_RESOLUTION_W) & mask), int((cfg >> (2 * GRID_RESOLUTION_W)) & mask)};
}

void rt_grid_model::reset() {
  for (Slot& s : slots_) s.state = State::Free;
  s1_.valid = s2_.valid = false;
  visitArb_ = idxArb_ = checkArb_ = doneArb_ = RoundRobin{};
  cellQ_.clear();
  idxQ_.clear();
  triQ_.clear();
  idxBuf_.clear();
  visitQ_.clear();
  resQ_.clear();
  credits_ = IDX_BUF_DEPTH;
}

void rt_grid_model::seq() {
  if (!rst_ni.read()) {
    reset();
    writeOutputs();
    state_changed_.notify();
    return;
  }

  // ---- Decisions of this cycle, from the registers at its start and the inputs.
  const int usable = std::min<int>(int(cfg_slots_i.read()), N);
  int alloc = -1;
  for (int s = 0; s < usable; ++s) {
    if (slots_[size_t(s)].state == State::Free) {
      alloc = s;
      break;
    }
  }
  const bool rayFire = ray_valid_i.read() && alloc >= 0;

  const int visitIdx = visitArb_.pick(N, [&](int k) { return slots_[size_t(k)].state == State::Visit; });
  const bool visitGo = visitIdx >= 0 && !cellQ_.full() && !visitQ_.full();
  const int idxIdx = idxArb_.pick(N, [&](int k) {
    const Slot& s = slots_[size_t(k)];
    return s.state == State::Fetch && s.issued != s.count;
  });
  const bool idxGo = idxIdx >= 0 && !idxQ_.full() && credits_ != 0;
  const int checkIdx = checkArb_.pick(N, [&](int k) {
    const Slot& s = slots_[size_t(k)];
    return s.state == State::Check && s.hasHit;
  });
  const int doneIdx = doneArb_.pick(N, [&](int k) { return slots_[size_t(k)].state == State::Done; });
  const bool doneGo = doneIdx >= 0 && !resQ_.full();
  const bool idxBufPop = !idxBuf_.empty() && !triQ_.full();

  // Memory responses (the RTL's assertions a_cell_rsp_slot, a_tri_rsp_slot, a_idx_buf_room).
  const bool cellRsp = cell_rsp_valid_i.read();
  int cellSlot = -1;
  fx::GridCell cellData;
  if (cellRsp) {
    cellSlot = int(uint32_t(cell_rsp_tag_i.read()) & SLOT_MASK);
    if (cellSlot >= N || slots_[size_t(cellSlot)].state != State::WaitCell) {
      fail(fmt::format("cell response for slot {}, which does not wait for one", cellSlot));
    }
    const auto v = fx::unpackFields(fx::kGridCellFields, fromPort<GRID_CELL_W>(cell_rsp_data_i.read()));
    cellData.first = uint32_t(v[0]);
    cellData.count = uint32_t(v[1]);
  }
  if (tri_rsp_valid_i.read()) {
    const uint32_t t = uint32_t(tri_rsp_tag_i.read()) & SLOT_MASK;
    if (t >= uint32_t(N) || slots_[t].state != State::Fetch) {
      fail(fmt::format("triangle response for slot {}, which is not fetching", t));
    }
  }
  const bool idxRsp = idx_rsp_valid_i.read();
  if (idxRsp && idxBuf_.full()) fail("index response with the index buffer full (credit error)");

  // rt_isect's result of this cycle: one closest-hit update.
  const bool resValid = isect_res_valid.read();
  int resSlot = -1;
  bool resTake = false;
  fx::IsectResult res;
  if (resValid) {
    res = fx::unpackResult(fromPort<ISECT_RES_W>(isect_res.read()));
    resSlot = int(res.rayId & SLOT_MASK);
    if (resSlot >= N) fail(fmt::format("rt_isect result for slot {}", resSlot));
    const Slot& s = slots_[size_t(resSlot)];
    resTake = res.hit && (!s.hasHit || fx::closerResult(res, s.best));
  }

  // The exit test of the granted slot (no stepping axis: the ray ends anyway).
  bool checkHolds = false;
  if (checkIdx >= 0) {
    const Slot& s = slots_[size_t(checkIdx)];
    checkHolds = s.dda.nextAxis() < 0 || s.dda.holds(s.best);
  }

  // Records pushed this cycle, from the registers at the start of the cycle.
  Visit visitRec;
  MemReq cellReq, idxReq;
  if (visitGo) {
    const Slot& s = slots_[size_t(visitIdx)];
    visitRec = {s.rayId, s.dda.cellId()};
    cellReq = {addrOf(s.dda.cellId()), uint32_t(visitIdx)};
  }
  if (idxGo) {
    const Slot& s = slots_[size_t(idxIdx)];
    idxReq = {addrOf(s.first + s.issued), uint32_t(idxIdx)};
  }
  grid_res_t doneRec{};
  if (doneGo) {
    const Slot& s = slots_[size_t(doneIdx)];
    const fx::u128 values[] = {s.rayId, s.cells, s.tests, s.hasHit ? 1u : 0u, s.best.primId,
                               s.best.tNum, s.best.det, s.best.uNum, s.best.vNum};
    doneRec = toPort<GRID_RESULT_W>(fx::packFields(fx::kGridResFields, values));
  }

  // ---- Register updates: the slots.
  for (int k = 0; k < N; ++k) {
    Slot& s = slots_[size_t(k)];
    State next = s.state;
    bool step = false;
    fx::GridDda stepped;
    switch (s.state) {
      case State::Free:
        if (rayFire && k == alloc) next = State::Setup;
        break;
      case State::Setup:
        if (s2_.valid && s2_.slot == k) next = State::Visit;
        break;
      case State::Visit:
        if (visitGo && k == visitIdx) next = State::WaitCell;
        break;
      case State::WaitCell:
        if (cellRsp && k == cellSlot) next = cellData.count == 0 ? State::Check : State::Fetch;
        break;
      case State::Fetch:
        if (s.received == s.count) next = State::Check;
        break;
      case State::Check:
        if (!s.hasHit || k == checkIdx) {
          const bool holds = s.hasHit && checkHolds;
          stepped = s.dda;
          const bool stays = !holds && stepped.nextAxis() >= 0 && stepped.advance();
          step = stays;
          next = stays ? State::Visit : State::Done;
        }
        break;
      case State::Done:
        if (doneGo && k == doneIdx) next = State::Free;
        break;
    }
    // Datapath (each register written only in its state, as the RTL's).
    if (s2_.valid && s2_.slot == k) {
      fx::QRay ray = fx::unpackRay(fromPort<ISECT_RAY_W>(s2_.ray));
      s.rayId = ray.id;
      s.dda = fx::GridDda::setup(resolution(), ray);
      ray.id = uint32_t(k);
      s.isectRay = toPort<ISECT_RAY_W>(fx::packWire(ray));
      s.cells = s.tests = 0;
      s.hasHit = false;
      s.best = fx::IsectResult{};
    }
    if (step) s.dda = stepped;
    if (visitGo && k == visitIdx) ++s.cells;
    if (s.state == State::WaitCell && cellRsp && k == cellSlot) {
      s.first = cellData.first;
      s.count = cellData.count;
      s.tests += cellData.count;
      s.issued = s.received = 0;
    }
    if (idxGo && k == idxIdx) ++s.issued;
    if (resValid && k == resSlot) {
      ++s.received;
      if (resTake) {
        s.hasHit = true;
        s.best = res;
      }
    }
    s.state = next;
  }

  // ---- FIFOs, credits, arbiter pointers, setup pipeline.
  if (!cellQ_.empty() && cell_req_ready_i.read()) cellQ_.pop();
  if (visitGo) cellQ_.push(cellReq);
  if (!visitQ_.empty() && visit_ready_i.read()) visitQ_.pop();
  if (visitGo) visitQ_.push(visitRec);
  if (!idxQ_.empty() && idx_req_ready_i.read()) idxQ_.pop();
  if (idxGo) idxQ_.push(idxReq);
  if (!triQ_.empty() && tri_req_ready_i.read()) triQ_.pop();
  if (idxBufPop) {
    triQ_.push(idxBuf_.front());
    idxBuf_.pop();
  }
  if (idxRsp) idxBuf_.push({addrOf(uint32_t(idx_rsp_data_i.read())), uint32_t(idx_rsp_tag_i.read()) & SLOT_MASK});
  if (!resQ_.empty() && res_ready_i.read()) resQ_.pop();
  if (doneGo) resQ_.push(doneRec);
  if (idxGo && !idxBufPop) --credits_;
  if (idxBufPop && !idxGo) ++credits_;

  if (visitGo) visitArb_.ack(visitIdx, N);
  if (idxGo) idxArb_.ack(idxIdx, N);
  if (checkIdx >= 0) checkArb_.ack(checkIdx, N);
  if (doneGo) doneArb_.ack(doneIdx, N);

  if (s1_.valid) {
    s2_.slot = s1_.slot;
    s2_.ray = s1_.ray;
  }
  s2_.valid = s1_.valid;
  if (rayFire) {
    s1_.slot = alloc;
    s1_.ray = ray_data_i.read();
  }
  s1_.valid = rayFire;

  writeOutputs();
  state_changed_.notify();  // immediate: comb() runs in this evaluation phase
}

void rt_grid_model::writeOutputs() {
  cell_req_valid_o.write(!cellQ_.empty());
  if (!cellQ_.empty()) {
    cell_req_addr_o.write(mem_addr_t(cellQ_.front().addr));
    cell_req_tag_o.write(slot_t(cellQ_.front().slot));
  }
  idx_req_valid_o.write(!idxQ_.empty());
  if (!idxQ_.empty()) {
    idx_req_addr_o.write(mem_addr_t(idxQ_.front().addr));
    idx_req_tag_o.write(slot_t(idxQ_.front().slot));
  }
  tri_req_valid_o.write(!triQ_.empty());
  if (!triQ_.empty()) {
    tri_req_addr_o.write(mem_addr_t(triQ_.front().addr));
    tri_req_tag_o.write(slot_t(triQ_.front().slot));
  }
  visit_valid_o.write(!visitQ_.empty());
  if (!visitQ_.empty()) {
    const fx::u128 values[] = {visitQ_.front().rayId, visitQ_.front().cellId};
    visit_data_o.write(toPort<GRID_VISIT_W>(fx::packFields(fx::kGridVisitFields, values)));
  }
  res_valid_o.write(!resQ_.empty());
  if (!resQ_.empty()) res_data_o.write(resQ_.front());
}

void rt_grid_model::comb() {
  isect_res_ready.write(true);  // rt_grid takes every rt_isect result
  const int usable = std::min<int>(int(cfg_slots_i.read()), N);
  bool ready = false;
  for (int s = 0; s < usable && !ready; ++s) ready = slots_[size_t(s)].state == State::Free;
  ray_ready_o.write(ready);
  const bool valid = tri_rsp_valid_i.read();
  const uint32_t tag = uint32_t(tri_rsp_tag_i.read()) & SLOT_MASK;
  if (valid && tag < uint32_t(N)) isect_ray.write(slots_[tag].isectRay);
  isect_tri.write(tri_rsp_data_i.read());
  isect_req_valid.write(valid);
  perf_isect_fire_o.write(valid && isect_req_ready.read());
}

}  // namespace lancer::sc
