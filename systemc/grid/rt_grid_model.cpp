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
constexpr uint32_t SLOT_MASK = (uint32_t(1) << rt_grid_unit::SLOT_W) - 1;

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
    : rt_trav_shell<rt_grid_unit>(name),
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
  sensitive << cfg_slots_i << isect_req_ready << state_changed_;
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
  for (Slot& s : slots_) s = Slot{};
  q_.clear();
  cellRsp_.valid = triRsp_.valid = false;
  cellArb_ = visitArb_ = idxArb_ = checkArb_ = doneArb_ = RoundRobin{};
}

void rt_grid_model::startCell(Slot& s, const fx::GridCell& data) {
  s.first = data.first;
  s.count = data.count;
  s.tests += data.count;
  s.issued = s.received = 0;
  if (data.count > 0) {
    s.state = State::Fetch;
  } else {
    cellDone(s);
  }
}

void rt_grid_model::cellDone(Slot& s) {
  if (s.hit.wantsCheck()) {
    s.state = State::Check;
  } else if (s.queue[size_t(s.head)].last) {
    s.state = State::Done;
  } else {
    nextCell(s);
  }
}

void rt_grid_model::nextCell(Slot& s) {
  s.head = (s.head + 1) % CELL_QUEUE;
  --s.queued;
  s.state = State::Visit;
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

  auto inFlight = [](const Slot& s) {
    return s.state == State::Visit || s.state == State::WaitCell || s.state == State::Fetch ||
           s.state == State::Check;
  };
  const int cellIdx = cellArb_.pick(N, [&](int k) {
    const Slot& s = slots_[size_t(k)];
    return inFlight(s) && s.frontierValid && s.queued < CELL_QUEUE;
  });
  const bool cellGo = cellIdx >= 0 && !q_.nodeQ.full();
  const int visitIdx = visitArb_.pick(N, [&](int k) {
    const Slot& s = slots_[size_t(k)];
    return s.state == State::Visit && s.queued > 0;
  });
  const bool visitGo = visitIdx >= 0 && !q_.visitQ.full();
  const int idxIdx = idxArb_.pick(N, [&](int k) {
    const Slot& s = slots_[size_t(k)];
    return s.state == State::Fetch && s.issued != s.count;
  });
  const bool idxGo = idxIdx >= 0 && !q_.idxQ.full() && q_.credits != 0;
  const int checkIdx = checkArb_.pick(N, [&](int k) { return slots_[size_t(k)].state == State::Check; });
  const int doneIdx = doneArb_.pick(N, [&](int k) {
    const Slot& s = slots_[size_t(k)];
    return s.state == State::Done && s.outstanding == 0;
  });
  const bool doneGo = doneIdx >= 0 && !q_.resQ.full();
  const bool idxBufPop = !q_.idxBuf.empty() && !q_.triQ.full();

  // Memory responses: cell and triangle responses from the boundary registers
  // (the RTL's assertions a_cell_rsp_slot, a_cell_rsp_head, a_tri_rsp_slot,
  // a_idx_buf_room).
  const bool cellRsp = cellRsp_.valid;
  int cellSlot = -1;
  fx::GridCell cellData;
  if (cellRsp) {
    cellSlot = int(cellRsp_.tag & SLOT_MASK);
    if (cellSlot >= N || slots_[size_t(cellSlot)].outstanding == 0) {
      fail(fmt::format("cell response for slot {}, which has no cell read outstanding", cellSlot));
    }
    const Slot& s = slots_[size_t(cellSlot)];
    if (s.state == State::WaitCell && s.outstanding != s.queued) {
      fail(fmt::format("cell response for slot {} in WAIT_CELL is not its head's", cellSlot));
    }
    std::array<uint32_t, size_t(fx::wireWords(GRID_CELL_W))> wire{};
    fromPort<GRID_CELL_W>(cellRsp_.data, wire);
    std::array<fx::u128, 2> v{};
    fx::unpackFields(fx::kGridCellFields, wire, v);
    cellData.first = uint32_t(v[0]);
    cellData.count = uint32_t(v[1]);
  }
  if (triRsp_.valid) {
    const uint32_t t = triRsp_.tag & SLOT_MASK;
    if (t >= uint32_t(N) || slots_[t].state != State::Fetch) {
      fail(fmt::format("triangle response for slot {}, which is not fetching", t));
    }
  }
  const bool idxRsp = idx_rsp_valid_i.read();
  if (idxRsp && q_.idxBuf.full()) fail("index response with the index buffer full (credit error)");

  // rt_isect's result of this cycle: one closest-hit update.
  const bool resValid = isect_res_valid.read();
  int resSlot = -1;
  bool resTake = false;
  fx::IsectResult res;
  if (resValid) {
    std::array<uint32_t, fx::kIsectResWords> wire{};
    fromPort<ISECT_RES_W>(isect_res.read(), wire);
    fx::unpackResult(wire, res);
    resSlot = int(res.rayId & SLOT_MASK);
    if (resSlot >= N) fail(fmt::format("rt_isect result for slot {}", resSlot));
    const Slot& s = slots_[size_t(resSlot)];
    resTake = s.hit.takes(res);
  }

  // The exit test of the granted slot, in its current cell (no stepping axis: the ray ends anyway).
  bool checkStops = false;
  if (checkIdx >= 0) {
    const Slot& s = slots_[size_t(checkIdx)];
    const CellEntry& e = s.queue[size_t(s.head)];
    checkStops = e.last || e.dda.nextAxis() < 0 || s.hit.settled() || e.dda.holds(s.hit.best);
  }

  // Records pushed this cycle, from the registers at the start of the cycle.
  rt_visit_entry visitRec;
  rt_mem_req cellReq, idxReq;
  if (cellGo) {
    const Slot& s = slots_[size_t(cellIdx)];
    cellReq = {addrOf(s.frontier.cellId()), uint32_t(cellIdx)};
  }
  if (visitGo) {
    const Slot& s = slots_[size_t(visitIdx)];
    visitRec = {s.rayId, s.queue[size_t(s.head)].cellId};
  }
  if (idxGo) {
    const Slot& s = slots_[size_t(idxIdx)];
    idxReq = {addrOf(s.first + s.issued), uint32_t(idxIdx)};
  }
  res_t doneRec{};
  if (doneGo) {
    const Slot& s = slots_[size_t(doneIdx)];
    const auto values = s.hit.resultValues(s.rayId, s.cells, s.tests);
    std::array<uint32_t, size_t(fx::wireWords(rt_grid_unit::RESULT_W))> wire{};
    fx::packFields(fx::kGridResFields, values, wire);
    doneRec = toPort<rt_grid_unit::RESULT_W>(wire);
  }

  // ---- Register updates of the slots, event by event (each names another slot,
  // except the cell grant and the cell response, which touch only the queue
  // bookkeeping and may meet any other event of their slot).
  // Queue positions from the start of the cycle: the pushed entry goes behind
  // the queued ones, a response fills the oldest entry still waiting for one.
  int pushAt = -1, fillAt = -1;
  if (cellGo) {
    const Slot& s = slots_[size_t(cellIdx)];
    pushAt = (s.head + s.queued) % CELL_QUEUE;
  }
  if (cellRsp) {
    const Slot& s = slots_[size_t(cellSlot)];
    fillAt = (s.head + s.queued - s.outstanding) % CELL_QUEUE;
  }
  const bool visitHeadIn =  // the granted visit's cell data is in, or arrives now
      visitGo && (slots_[size_t(visitIdx)].outstanding < slots_[size_t(visitIdx)].queued || cellSlot == visitIdx);

  if (rayFire) slots_[size_t(alloc)].state = State::Setup;
  if (q_.setup.s2.valid) {
    Slot& s = slots_[size_t(q_.setup.s2.slot)];
    fx::QRay ray;
    std::array<uint32_t, fx::kIsectRayWords> wire{};
    fromPort<ISECT_RAY_W>(q_.setup.s2.ray, wire);
    fx::unpackRay(wire, ray);
    s.rayId = ray.id;
    s.frontier = fx::GridDda::setup(resolution(), ray);
    s.frontierValid = true;
    ray.id = uint32_t(q_.setup.s2.slot);
    fx::packWire(ray, wire);
    s.isectRay = toPort<ISECT_RAY_W>(wire);
    s.head = s.queued = 0;
    s.cells = s.tests = 0;
    s.hit.start(ray);
    s.state = State::Visit;
  }
  if (cellRsp) {
    Slot& s = slots_[size_t(cellSlot)];
    s.queue[size_t(fillAt)].data = cellData;
    --s.outstanding;
  }
  if (cellGo) {
    // The frontier's read: it joins the queue with its exit test, and the DDA steps.
    Slot& s = slots_[size_t(cellIdx)];
    CellEntry& e = s.queue[size_t(pushAt)];
    e.dda = s.frontier;
    e.cellId = s.frontier.cellId();
    const bool stays = s.frontier.nextAxis() >= 0 && s.frontier.advance();
    e.last = !stays;
    if (!stays) s.frontierValid = false;
    ++s.queued;
    ++s.outstanding;
  }
  if (visitGo) {
    Slot& s = slots_[size_t(visitIdx)];
    ++s.cells;
    if (visitHeadIn) {
      startCell(s, s.queue[size_t(s.head)].data);  // (filled above if it arrived now)
    } else {
      s.state = State::WaitCell;
    }
  }
  if (cellRsp && slots_[size_t(cellSlot)].state == State::WaitCell && cellSlot != visitIdx) {
    Slot& s = slots_[size_t(cellSlot)];
    startCell(s, cellData);
  }
  if (idxGo) ++slots_[size_t(idxIdx)].issued;
  if (resValid) {
    Slot& s = slots_[size_t(resSlot)];
    ++s.received;
    if (resTake) {
      s.hit.take(res);
    }
    if (s.received == s.count) cellDone(s);
  }
  if (checkIdx >= 0) {
    Slot& s = slots_[size_t(checkIdx)];
    if (checkStops) {
      s.state = State::Done;
    } else {
      nextCell(s);
    }
  }
  if (doneGo) slots_[size_t(doneIdx)].state = State::Free;

  // ---- FIFOs, credits, arbiter pointers, setup pipeline.
  if (!q_.nodeQ.empty() && cell_req_ready_i.read()) q_.nodeQ.pop();
  if (cellGo) q_.nodeQ.push(cellReq);
  if (!q_.visitQ.empty() && visit_ready_i.read()) q_.visitQ.pop();
  if (visitGo) q_.visitQ.push(visitRec);
  if (!q_.idxQ.empty() && idx_req_ready_i.read()) q_.idxQ.pop();
  if (idxGo) q_.idxQ.push(idxReq);
  if (!q_.triQ.empty() && tri_req_ready_i.read()) q_.triQ.pop();
  if (idxBufPop) {
    q_.triQ.push(q_.idxBuf.front());
    q_.idxBuf.pop();
  }
  if (idxRsp) q_.idxBuf.push({addrOf(uint32_t(idx_rsp_data_i.read())), uint32_t(idx_rsp_tag_i.read()) & SLOT_MASK});
  if (!q_.resQ.empty() && res_ready_i.read()) q_.resQ.pop();
  if (doneGo) q_.resQ.push(doneRec);
  if (idxGo && !idxBufPop) --q_.credits;
  if (idxBufPop && !idxGo) ++q_.credits;

  if (cellGo) cellArb_.ack(cellIdx, N);
  if (visitGo) visitArb_.ack(visitIdx, N);
  if (idxGo) idxArb_.ack(idxIdx, N);
  if (checkIdx >= 0) checkArb_.ack(checkIdx, N);
  if (doneGo) doneArb_.ack(doneIdx, N);

  q_.setup.shift();
  if (rayFire) q_.setup.load(alloc, ray_data_i.read());

  cellRsp_.valid = cell_rsp_valid_i.read();
  if (cellRsp_.valid) {
    cellRsp_.tag = uint32_t(cell_rsp_tag_i.read());
    cellRsp_.data = cell_rsp_data_i.read();
  }
  triRsp_.valid = tri_rsp_valid_i.read();
  if (triRsp_.valid) {
    triRsp_.tag = uint32_t(tri_rsp_tag_i.read());
    triRsp_.data = tri_rsp_data_i.read();
  }

  writeOutputs();
  state_changed_.notify();  // immediate: comb() runs in this evaluation phase
}

void rt_grid_model::writeOutputs() {
  cell_req_valid_o.write(!q_.nodeQ.empty());
  if (!q_.nodeQ.empty()) writeRequest(q_.nodeQ, cell_req_addr_o, cell_req_tag_o);
  idx_req_valid_o.write(!q_.idxQ.empty());
  if (!q_.idxQ.empty()) writeRequest(q_.idxQ, idx_req_addr_o, idx_req_tag_o);
  tri_req_valid_o.write(!q_.triQ.empty());
  if (!q_.triQ.empty()) writeRequest(q_.triQ, tri_req_addr_o, tri_req_tag_o);
  visit_valid_o.write(!q_.visitQ.empty());
  if (!q_.visitQ.empty()) {
    const fx::u128 values[] = {q_.visitQ.front().rayId, q_.visitQ.front().id};
    std::array<uint32_t, size_t(fx::wireWords(rt_grid_unit::VISIT_W))> wire{};
    fx::packFields(fx::kGridVisitFields, values, wire);
    visit_data_o.write(toPort<rt_grid_unit::VISIT_W>(wire));
  }
  res_valid_o.write(!q_.resQ.empty());
  if (!q_.resQ.empty()) res_data_o.write(q_.resQ.front());
  bool stepReady = false;
  for (const Slot& s : slots_) stepReady = stepReady || (s.state == State::Visit && s.queued > 0);
  perf_step_ready_o.write(stepReady);
}

void rt_grid_model::comb() {
  isect_res_ready.write(true);  // rt_grid takes every rt_isect result
  const int usable = std::min<int>(int(cfg_slots_i.read()), N);
  bool ready = false;
  for (int s = 0; s < usable && !ready; ++s) ready = slots_[size_t(s)].state == State::Free;
  ray_ready_o.write(ready);
  const bool valid = triRsp_.valid;
  const uint32_t tag = triRsp_.tag & SLOT_MASK;
  if (valid && tag < uint32_t(N)) isect_ray.write(slots_[tag].isectRay);
  if (valid) isect_tri.write(triRsp_.data);
  isect_req_valid.write(valid);
  perf_isect_fire_o.write(valid && isect_req_ready.read());
}

}  // namespace lancer::sc
