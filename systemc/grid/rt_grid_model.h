#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>


#include "common/rt_trav_shell_model.h"
#include "golden/grid.h"
#include "grid/rt_grid_unit.h"

#ifndef LANCER_GRID_CELL_QUEUE
#error "LANCER_GRID_CELL_QUEUE must come from the build (rtl/grid/unit.cmake)"
#endif

namespace lancer::sc {

// rt_grid's CellQueue as the Verilated model is built: cells per slot read and not finished.
inline constexpr int CELL_QUEUE = LANCER_GRID_CELL_QUEUE;

// rt_grid_model: hand-written cycle model of rtl/grid/rt_grid.sv, meant to
// match it cycle for cycle and bit for bit at its ports; docs/grid-unit.md is
// the contract (slot state machine, cell prefetch, "Per-cycle behaviour of
// rt_grid"). The shell's work (rt_trav_shell: allocation, arbiters, FIFOs,
// credits, u_isect, closest hits, results) is rt_trav_shell_model's with
// RegRsp (cell and triangle responses are registered at the boundary: a
// response sampled at the edge ending cycle c is used in cycle c+1); this
// model holds the walk of rt_grid_slots.sv and the setup of rt_grid_setup.sv.
//
//   cycle() once per rising edge (the shell's clock(); its reset() calls
//           resetWalk()): the cycle as an outline of named steps, each deciding from
//           the registers at the start of the cycle and the inputs.
//   u_isect rt_isect's timing inside the shell, or the Verilated Vrt_isect_sc
//           (constructor argument: the mixed system).
//
// No arithmetic is duplicated: per-ray setup, the step, the exit test and the
// closest-hit order are fx::GridDda::setup/advance/holds and fx::closerResult
// of the golden model (sw/golden/grid.h); the model only schedules them. Each
// slot is a C++ record (state, frontier DDA, a ring of CELL_QUEUE cell
// entries with counts), the RTL's one-hot vectors and thermometer codes are
// not mirrored: the two are independent formulations of the same contract.
// Latency and throughput are the RTL's: setup 1 + GRID_SETUP_LATENCY cycles
// (SETUP -> VISIT), per cycle at most one ray accepted, one cell read (one DDA
// step), one visit, one index read, one triangle read, one test, one result
// update, one exit test and one result.
class rt_grid_model : public rt_trav_shell_model<rt_grid_unit, /*RegRsp=*/true> {
 public:
  explicit rt_grid_model(rt_isect_impl isect = rt_isect_impl::model);

 private:
  enum class State : uint8_t { Free, Setup, Visit, WaitCell, Fetch, Check, Done };

  // One entry of a slot's cell queue: a cell whose read has been issued.
  struct CellEntry {
    fx::GridDda dda;       // the DDA in this cell (its exit test)
    uint32_t cellId = 0;
    bool last = false;     // the ray leaves the grid after this cell
    fx::GridCell data;     // the cell table entry, once its response is in
  };

  // One ray slot of rt_grid_slots.
  struct Slot {
    State state = State::Free;
    fx::GridDda frontier;       // the next cell to request
    bool frontierValid = false; // it lies in the grid
    std::array<CellEntry, CELL_QUEUE> queue{};
    int head = 0;               // queue[head]: the cell being entered or visited
    int queued = 0;             // entries: cells requested and not finished
    int outstanding = 0;        // cell reads without their response (the newest entries)
  };

  // The cell response of the cycle, decoded.
  struct CellIn {
    int slot = -1;         // -1: none
    bool waiting = false;  // its slot is in WAIT_CELL
    fx::GridCell data;
  };

  // The steps of a cycle (seq), each named for what it does.
  void cycle() override;
  void resetWalk() override;
  wants_t wants() const;
  void refreshWants(int k);
  bool headReady(int k) const;
  CellIn cellResponse();
  void load(int k);
  void fillCell(const CellIn& in);
  void requestCell(int k);
  void visitCell(int k, bool headIn);
  void check(int k);
  void finish(int k);
  // A cell's data is in: its tests begin, or it is done at once (no triangles).
  void startCell(int k, const fx::GridCell& data);
  // Every result of the current cell is in: CHECK with a hit, else DONE after
  // the last cell, else on to the next cell.
  void cellDone(int k);
  void nextCell(int k);
  fx::GridRes resolution() const;

  std::vector<Slot> slots_;
  // The want vectors as the slot registers stand, stepping and preparing
  // slots included: a cycle refreshes the slots its events touched (at most
  // one event a slot names per arbiter, allocation, setup, response), so no
  // cycle scans every slot.
  wants_t held_;
  // The slots granted a cell one and two cycles ago: rt_grid_slots steps the
  // first's frontier in this cycle and prepares the second's next step
  // (step_q), so neither asks for a cell now.
  int stepping_ = -1;
  int preparing_ = -1;
};

}  // namespace lancer::sc
