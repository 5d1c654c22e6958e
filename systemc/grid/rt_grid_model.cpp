#include "grid/rt_grid_model.h"

#include <array>
#include <utility>

#include <fmt/format.h>

namespace lancer::sc {

rt_grid_model::rt_grid_model(rt_isect_impl isect) : rt_trav_shell_model(isect), slots_(size_t(N)) {}

// One cycle: the shell's grants and responses, then the walk's events slot
// by slot (each names another slot, except the cell grant and the cell
// response, which touch only the queue bookkeeping and may meet any other
// event of their slot), then the shell's registers and outputs.
void rt_grid_model::cycle() {
  const wants_t w = wants();
  const rt_trav_grants g = grant(w);
  const CellIn cell = cellResponse();
  const rt_isect_result res = intersect(w.expect);
  const bool visitHeadIn = g.visit >= 0 && (headReady(g.visit) || cell.slot == g.visit);

  if (g.alloc >= 0) slots_[size_t(g.alloc)].state = State::Setup;
  if (loadSlot() >= 0) load(loadSlot());
  fillCell(cell);
  if (g.node >= 0) requestCell(g.node);
  preparing_ = std::exchange(stepping_, g.node);
  if (g.visit >= 0) visitCell(g.visit, visitHeadIn);
  if (cell.waiting && cell.slot != g.visit) startCell(cell.slot, cell.data);
  if (res.valid && res.last) cellDone(res.slot);
  if (g.check >= 0) check(g.check);
  if (g.done >= 0) finish(g.done);
  for (const int k : {g.alloc, loadSlot(), cell.slot, g.node, g.visit, res.valid ? res.slot : -1, g.check, g.done}) {
    if (k >= 0) refreshWants(k);
  }

  endCycle(g, held_.visit.any());
}

void rt_grid_model::resetWalk() {
  for (Slot& s : slots_) s = Slot{};
  held_ = wants_t{};
  stepping_ = -1;
  preparing_ = -1;
}

// rt_grid_slots' want vectors: the slots' own, less the slots stepping or
// preparing a step (they ask for no cell).
rt_grid_model::wants_t rt_grid_model::wants() const {
  wants_t w = held_;
  for (const int k : {stepping_, preparing_}) {
    if (k >= 0) w.node.reset(k);
  }
  return w;
}

// Slot k's bits of the want vectors, from its registers.
void rt_grid_model::refreshWants(int k) {
  const Slot& s = slots_[size_t(k)];
  for (slot_mask* m : {&held_.node, &held_.visit, &held_.check, &held_.done, &held_.expect}) m->reset(k);
  switch (s.state) {
    case State::Visit:
      if (s.queued > 0) held_.visit.set(k);
      break;
    case State::Fetch: held_.expect.set(k); break;
    case State::Check: held_.check.set(k); break;
    case State::Done:
      if (s.outstanding == 0) held_.done.set(k);
      break;
    default: break;
  }
  const bool inFlight = s.state == State::Visit || s.state == State::WaitCell || s.state == State::Fetch ||
                        s.state == State::Check;
  if (inFlight && s.frontierValid && s.queued < CELL_QUEUE) held_.node.set(k);
}

// The head entry's cell data is in (its response came in an earlier cycle).
bool rt_grid_model::headReady(int k) const {
  const Slot& s = slots_[size_t(k)];
  return s.outstanding < s.queued;
}

// The registered cell response, with the RTL's assertions a_cell_rsp_slot and a_cell_rsp_head.
rt_grid_model::CellIn rt_grid_model::cellResponse() {
  const node_rsp rsp = nodeResponse();
  CellIn in;
  if (!rsp.valid) return in;
  in.slot = rsp.slot;
  if (in.slot >= N || slots_[size_t(in.slot)].outstanding == 0) {
    fail(fmt::format("cell response for slot {}, which has no cell read outstanding", in.slot));
  }
  const Slot& s = slots_[size_t(in.slot)];
  in.waiting = s.state == State::WaitCell;
  if (in.waiting && s.outstanding != s.queued) {
    fail(fmt::format("cell response for slot {} in WAIT_CELL is not its head's", in.slot));
  }
  std::array<uint32_t, size_t(fx::wireWords(rt_grid_unit::NODE_W))> wire{};
  fromValue<rt_grid_unit::NODE_DATA_W>(*rsp.data, wire);
  std::array<fx::u128, 2> v{};
  fx::unpackFields(fx::kGridCellFields, wire, v);
  in.data.first = uint32_t(v[0]);
  in.data.count = uint32_t(v[1]);
  return in;
}

fx::GridRes rt_grid_model::resolution() const {
  const uint32_t cfg = uint32_t(cfg_i.read());
  constexpr uint32_t mask = (uint32_t(1) << fx::kGridResolutionBits) - 1;
  return {int(cfg & mask), int((cfg >> fx::kGridResolutionBits) & mask), int((cfg >> (2 * fx::kGridResolutionBits)) & mask)};
}

// SETUP -> VISIT at the end of accept + GRID_SETUP_LATENCY: the DDA's setup (rt_grid_setup).
void rt_grid_model::load(int k) {
  Slot& s = slots_[size_t(k)];
  s.frontier = fx::GridDda::setup(resolution(), loadRay(k));
  s.frontierValid = true;
  s.head = s.queued = 0;
  s.state = State::Visit;
}

// The response fills the oldest entry still waiting for one.
void rt_grid_model::fillCell(const CellIn& in) {
  if (in.slot < 0) return;
  Slot& s = slots_[size_t(in.slot)];
  s.queue[size_t((s.head + s.queued - s.outstanding) % CELL_QUEUE)].data = in.data;
  --s.outstanding;
}

// The frontier's read: it joins the queue behind the queued cells with its exit test, and the DDA steps.
void rt_grid_model::requestCell(int k) {
  Slot& s = slots_[size_t(k)];
  pushNode(k, s.frontier.cellId());
  CellEntry& e = s.queue[size_t((s.head + s.queued) % CELL_QUEUE)];
  e.dda = s.frontier;
  e.cellId = s.frontier.cellId();
  const bool stays = s.frontier.nextAxis() >= 0 && s.frontier.advance();
  e.last = !stays;
  if (!stays) s.frontierValid = false;
  ++s.queued;
  ++s.outstanding;
}

// VISIT: the head cell's visit record; its tests begin once its data is in.
void rt_grid_model::visitCell(int k, bool headIn) {
  Slot& s = slots_[size_t(k)];
  pushVisit(k, s.queue[size_t(s.head)].cellId);
  if (headIn) {
    startCell(k, s.queue[size_t(s.head)].data);  // (filled above if it arrived now)
  } else {
    s.state = State::WaitCell;
  }
}

// The exit test in the current cell (no stepping axis: the ray ends anyway).
void rt_grid_model::check(int k) {
  Slot& s = slots_[size_t(k)];
  const CellEntry& e = s.queue[size_t(s.head)];
  const rt_closest_record& h = hit(k);
  if (e.last || e.dda.nextAxis() < 0 || h.settled() || e.dda.holds(h.best)) {
    s.state = State::Done;
  } else {
    nextCell(k);
  }
}

void rt_grid_model::finish(int k) {
  finishRay(k);
  slots_[size_t(k)].state = State::Free;
}

void rt_grid_model::startCell(int k, const fx::GridCell& data) {
  startRun(k, data.first, data.count);
  if (data.count > 0) {
    slots_[size_t(k)].state = State::Fetch;
  } else {
    cellDone(k);
  }
}

void rt_grid_model::cellDone(int k) {
  Slot& s = slots_[size_t(k)];
  if (hit(k).wantsCheck()) {
    s.state = State::Check;
  } else if (s.queue[size_t(s.head)].last) {
    s.state = State::Done;
  } else {
    nextCell(k);
  }
}

void rt_grid_model::nextCell(int k) {
  Slot& s = slots_[size_t(k)];
  s.head = (s.head + 1) % CELL_QUEUE;
  --s.queued;
  s.state = State::Visit;
}

}  // namespace lancer::sc
