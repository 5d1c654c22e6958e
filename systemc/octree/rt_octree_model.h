#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <systemc>

#include "common/rt_trav_model_parts.h"
#include "common/rt_trav_shell.h"
#include "golden/octree.h"
#include "octree/rt_octree_types.h"
#include "octree/rt_octree_unit.h"

namespace lancer::sc {

// rt_octree_model: hand-written cycle model of rtl/octree/rt_octree.sv, meant to
// match it cycle for cycle and bit for bit at its ports; docs/octree-unit.md,
// "Micro-architecture of rt_octree", is the contract (slot registers and state
// machine, arbiters, FIFOs, credits, rt_isect timing), and docs/systemc.md
// states how this model reads the points the text leaves open.
//
//   seq()   SC_METHOD on clk_i.posedge (and rst_ni.negedge, the RTL's async
//           reset): every decision of the cycle from the registers at its
//           start and the inputs (allocation, the round-robin arbiters,
//           FIFO room, credits, the node responses, the closest-hit update,
//           the exit test, DESCEND and advance), then every register update,
//           then the flop-driven outputs (FIFO heads, ray_ready_o and
//           perf_step_ready_o, which depend on registers only).
//   comb()  SC_METHOD for the one combinational path from an input to an
//           output: perf_isect_fire_o = tri_rsp_valid_i (rt_isect always takes).
//   u_isect rt_isect's timing (ISECT_LATENCY stages, never stalls, results
//           always taken), inside this model: a triangle response in cycle c
//           enters with its slot's ray, and its fx::intersect() result is
//           absorbed in cycle c + ISECT_LATENCY. (No SystemC signals or sc_bv
//           conversions on this path: it is the model's hottest.)
//
// No arithmetic is duplicated: the per-ray setup is fx::OctreeRaySetup, the
// first child fx::firstChild, the successor fx::nextChild, the exit test
// fx::hitWithin, the closest-hit order fx::closerResult, the test fx::intersect
// — the golden model's code, scheduled as the RTL schedules it. The parameters
// move as the micro-architecture says (halvings down, 2·t1 − t0 sideways and up:
// no parameters on the stack).
//
// Speed: per-state slot masks; the arbiters find the next requester with bit
// scans, and only slots that act on their own in a cycle (DESCEND, FETCH with
// every result in) or are granted an advance lane are visited.
class rt_octree_model : public rt_trav_shell<rt_octree_unit> {
 public:
  // The ports of rt_trav_shell, and the unit's own:
  sc_core::sc_in<cfg_t> cfg_root_i{"cfg_root_i"};

  sc_core::sc_out<bool> node_req_valid_o{"node_req_valid_o"};
  sc_core::sc_in<bool> node_req_ready_i{"node_req_ready_i"};
  sc_core::sc_out<mem_addr_t> node_req_addr_o{"node_req_addr_o"};
  sc_core::sc_out<slot_t> node_req_tag_o{"node_req_tag_o"};
  sc_core::sc_in<bool> node_rsp_valid_i{"node_rsp_valid_i"};
  sc_core::sc_in<node_data_t> node_rsp_data_i{"node_rsp_data_i"};
  sc_core::sc_in<slot_t> node_rsp_tag_i{"node_rsp_tag_i"};

  SC_HAS_PROCESS(rt_octree_model);
  explicit rt_octree_model(sc_core::sc_module_name name);

  static constexpr int N = octree::RAYS_IN_FLIGHT;

  // A set of slots (N bits); the arbiters' request vectors.
  class SlotMask {
   public:
    static constexpr int kWords = (N + 63) / 64;
    void set(int k) { w_[size_t(k >> 6)] |= uint64_t(1) << (k & 63); }
    void reset(int k) { w_[size_t(k >> 6)] &= ~(uint64_t(1) << (k & 63)); }
    bool test(int k) const { return (w_[size_t(k >> 6)] >> (k & 63)) & 1; }
    bool any() const;
    void clear() { w_.fill(0); }
    int lowest() const;                // -1 if empty
    int lowestBelow(int limit) const;  // the lowest member < limit, or -1
    int pickFrom(int from) const;      // rt_rr_arb: the lowest member at or after `from`, cyclically; -1 if empty
    SlotMask operator|(const SlotMask& o) const;
    template <class F>
    void forEach(F f) const {
      for (int i = 0; i < kWords; ++i) {
        for (uint64_t m = w_[size_t(i)]; m != 0; m &= m - 1) f(i * 64 + __builtin_ctzll(m));
      }
    }

   private:
    std::array<uint64_t, kWords> w_{};
  };

 private:
  enum class State : uint8_t {
    Free, Setup, Enter, GroupReq, WaitGroup, Descend, Fetch, Check, Next, RefillReq, WaitRefill, Done
  };

  static constexpr int MAX_STACK = octree::MAX_DEPTH;  // P entries: levels 0 .. P-1

  struct StackEntry {
    uint32_t first = 0;  // the level's child-group base
    uint8_t child = 0;   // which of its children the walk is in (mirrored numbering)
  };

  // One slot's registers (docs/octree-unit.md, "Slot registers").
  struct Slot {
    State state = State::Free;
    uint32_t rayId = 0;               // the ray's own id (visit and result records)
    fx::QRay ray;                     // with id = the slot index, as it enters u_isect
    fx::OctreeRaySetup setup;         // a, o', active, common, dominant
    std::array<fx::OctT, 3> t0{}, t1{};  // the current node's parameters
    uint32_t nodeId = 0;
    fx::OctreeNode rec;
    int depth = 0;
    std::array<StackEntry, MAX_STACK> stack{};
    std::array<fx::OctreeNode, fx::kOctreeChildren> group{};
    bool groupValid = false;
    uint32_t nodes = 0, tests = 0, issued = 0, received = 0;
    rt_closest_record hit;
  };

  // rt_rr_arb's pointer: grants the lowest requester at or after it; moves past a used grant.
  struct RoundRobin {
    int ptr = 0;
    int pick(const SlotMask& want) const { return want.pickFrom(ptr); }
    void ack(int granted) { ptr = granted + 1 == N ? 0 : granted + 1; }
  };

  // u_isect: ISECT_LATENCY stages of {valid, result}.
  struct IsectStage {
    bool valid = false;
    fx::IsectResult res;
  };

  void seq();
  void comb();
  void reset();
  enum Flag { NODE_VALID, IDX_VALID, TRI_VALID, VISIT_VALID, RES_VALID, RAY_READY, STEP_READY, FLAGS };
  void writeOutputs(bool all);
  void writeFlag(sc_core::sc_out<bool>& port, Flag f, bool value, bool all);
  void setState(int k, State s);
  void load(int k, const isect_ray_t& port);
  void enter(int k);
  void descend(int k);
  void advance(int k);
  void fetchRequestUpdate(int k);
  [[noreturn]] void fail(const std::string& what) const;

  std::array<Slot, N> slots_{};
  // Slots by what they wait for or do this cycle.
  // advWant_: NEXT and CHECK without a hit, waiting for an advance lane;
  // self_: DESCEND and FETCH with every result in, acting on their own.
  SlotMask free_, enter_, nodeWant_, idxWant_, checkWant_, advWant_, done_, self_;
  rt_trav_fifos<res_t> q_;  // the shell's queues
  RoundRobin visitArb_, nodeArb_, idxArb_, checkArb_, doneArb_;
  std::array<RoundRobin, octree::ADV_LANES> advArb_{};  // lane l takes what lanes before it left
  std::array<IsectStage, ISECT_LATENCY> isect_{};
  size_t isectPos_ = 0;
  // Which FIFO heads changed since the outputs were last written.
  bool nodeHead_ = true, idxHead_ = true, triHead_ = true, visitHead_ = true, resHead_ = true;
  std::array<bool, FLAGS> flags_{};  // the flag outputs as last written
};

}  // namespace lancer::sc
