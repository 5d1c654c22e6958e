#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <systemc>

#include "common/rt_trav_model_parts.h"
#include "common/rt_trav_shell.h"
#include "golden/grid.h"
#include "grid/rt_grid_types.h"
#include "grid/rt_grid_unit.h"
#include "isect/rt_isect_top.h"

namespace lancer::sc {

// rt_grid_model: hand-written cycle model of rtl/grid/rt_grid.sv (with
// rt_grid_setup, rt_grid_slots, rt_fifo, rt_rr_arb), meant to match it cycle
// for cycle and bit for bit at its ports; docs/grid-unit.md is the contract
// (slot state machine, cell prefetch, "Per-cycle behaviour of rt_grid").
//
//   seq()   SC_METHOD on clk_i.posedge (and rst_ni.negedge, the RTL's async
//           reset): every decision of the cycle from the registers at its start
//           and the inputs (allocation, the five round-robin arbiters, FIFO
//           room, credits, the cell responses, the closest-hit update, the exit
//           test), then every register update, then the flop-driven outputs.
//   comb()  SC_METHOD for the RTL's combinational paths: the registered
//           triangle response with its slot's ray into u_isect,
//           perf_isect_fire_o, and ray_ready_o (free slots below cfg_slots_i).
// Cell and triangle responses are registered at the boundary, as in the RTL:
// a response sampled at the edge ending cycle c is used in cycle c+1.
//   u_isect the intersection pipeline, instantiated as rt_grid instantiates
//           rt_isect (req_ready_o unused: res_ready_i is tied to 1): either the
//           cycle model rt_isect_model or the Verilated Vrt_isect_sc, chosen
//           at construction.
//
// No arithmetic is duplicated: per-ray setup, the step, the exit test and the
// closest-hit order are fx::GridDda::setup/advance/holds and fx::closerResult
// of the golden model (sw/golden/grid.h); the model only schedules them. Each
// slot is a C++ record (state, frontier DDA, a ring of CELL_QUEUE cell
// entries with counts), the RTL's one-hot vectors and thermometer codes are
// not mirrored: the two are independent formulations of the same contract.
// Latency and throughput are the RTL's: setup 3 cycles (SETUP -> VISIT), per
// cycle at most one ray accepted, one cell read (one DDA step), one visit,
// one index read, one triangle read, one test, one result update, one exit
// test and one result.
class rt_grid_model : public rt_trav_shell<rt_grid_unit> {
 public:
  // The ports of rt_trav_shell, and the unit's own:
  sc_core::sc_in<cfg_t> cfg_res_i{"cfg_res_i"};

  sc_core::sc_out<bool> cell_req_valid_o{"cell_req_valid_o"};
  sc_core::sc_in<bool> cell_req_ready_i{"cell_req_ready_i"};
  sc_core::sc_out<mem_addr_t> cell_req_addr_o{"cell_req_addr_o"};
  sc_core::sc_out<slot_t> cell_req_tag_o{"cell_req_tag_o"};
  sc_core::sc_in<bool> cell_rsp_valid_i{"cell_rsp_valid_i"};
  sc_core::sc_in<node_data_t> cell_rsp_data_i{"cell_rsp_data_i"};
  sc_core::sc_in<slot_t> cell_rsp_tag_i{"cell_rsp_tag_i"};

  SC_HAS_PROCESS(rt_grid_model);
  explicit rt_grid_model(sc_core::sc_module_name name, rt_isect_impl isect = rt_isect_impl::model);
  ~rt_grid_model() override;

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
    uint32_t rayId = 0;         // the ray's own id (visit and result records)
    isect_ray_t isectRay{};     // the ray with ray_id = slot index, for u_isect
    fx::GridDda frontier;       // the next cell to request
    bool frontierValid = false; // it lies in the grid
    std::array<CellEntry, CELL_QUEUE> queue{};
    int head = 0;               // queue[head]: the cell being entered or visited
    int queued = 0;             // entries: cells requested and not finished
    int outstanding = 0;        // cell reads without their response (the newest entries)
    uint32_t cells = 0, tests = 0;
    uint32_t first = 0, count = 0, issued = 0, received = 0;  // the current cell
    rt_closest_record hit;
  };

  // rt_rr_arb: the lowest requester at or after the pointer, cyclically.
  struct RoundRobin {
    int ptr = 0;
    template <class Want>
    int pick(int n, Want want) const {
      for (int k = ptr; k < n; ++k)
        if (want(k)) return k;
      for (int k = 0; k < ptr; ++k)
        if (want(k)) return k;
      return -1;
    }
    void ack(int granted, int n) { ptr = granted + 1 == n ? 0 : granted + 1; }
  };

  // The boundary registers of the cell and triangle responses.
  struct CellRsp {
    bool valid = false;
    uint32_t tag = 0;
    node_data_t data{};
  };
  struct TriRsp {
    bool valid = false;
    uint32_t tag = 0;
    isect_tri_t data{};
  };

  void seq();
  void comb();
  // A cell's data is in: its tests begin, or it is done at once (no triangles).
  void startCell(Slot& s, const fx::GridCell& data);
  // Every result of the current cell is in: CHECK with a hit, else DONE after
  // the last cell, else on to the next cell.
  static void cellDone(Slot& s);
  static void nextCell(Slot& s);
  void reset();
  void writeOutputs();
  fx::GridRes resolution() const;
  [[noreturn]] void fail(const std::string& what) const;

  // u_isect and its signals, named after rt_isect's ports as rt_grid connects them.
  sc_core::sc_signal<bool> isect_req_valid{"isect_req_valid"};
  sc_core::sc_signal<bool> isect_req_ready{"isect_req_ready"};
  sc_core::sc_signal<isect_ray_t> isect_ray{"isect_ray"};
  sc_core::sc_signal<isect_tri_t> isect_tri{"isect_tri"};
  sc_core::sc_signal<bool> isect_res_valid{"isect_res_valid"};
  sc_core::sc_signal<bool> isect_res_ready{"isect_res_ready"};
  sc_core::sc_signal<isect_res_t> isect_res{"isect_res"};
  std::unique_ptr<sc_core::sc_module> u_isect;

  std::vector<Slot> slots_;
  rt_trav_fifos<res_t> q_;  // the shell's queues
  CellRsp cellRsp_;
  TriRsp triRsp_;
  RoundRobin cellArb_, visitArb_, idxArb_, checkArb_, doneArb_;
  sc_core::sc_event state_changed_;
};

}  // namespace lancer::sc
