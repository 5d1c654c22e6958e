#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <systemc>

#include "common/rt_trav_ports.h"
#include "common/rt_trav_tb.h"
#include "common/rt_trav_unit.h"

namespace lancer::sc {

// The suspension ports' signals of a unit that sets walks aside (the treelet
// schedule, which only the run loop drives: docs/scheduling.md). Here nothing
// drives the inputs (suspension off) and nothing reads the outputs.
template <class Unit, bool = Unit::kSuspends>
struct rt_suspend_wires {
  template <class Dut>
  void bindSuspendPorts(Dut&) {}
};
template <class Unit>
struct rt_suspend_wires<Unit, true> {
  sc_core::sc_signal<bool> cfg_suspend_i{"cfg_suspend_i"};
  sc_core::sc_signal<vl_port_t<Unit::BLOCK_SHIFT_W>> cfg_block_shift_i{"cfg_block_shift_i"};
  sc_core::sc_signal<bool> ray_resume_i{"ray_resume_i"};
  sc_core::sc_signal<vl_port_t<Unit::WALK_W>> ray_walk_i{"ray_walk_i"};
  sc_core::sc_signal<bool> res_suspended_o{"res_suspended_o"};
  sc_core::sc_signal<vl_port_t<Unit::WALK_W>> res_walk_o{"res_walk_o"};
  // A DUT with the ports (the Verilated RTL's SystemC class) on these signals.
  template <class Dut>
  void bindSuspendPorts(Dut& dut) {
    if constexpr (requires { dut.ray_resume_i; }) {
      dut.cfg_suspend_i(cfg_suspend_i);
      dut.cfg_block_shift_i(cfg_block_shift_i);
      dut.ray_resume_i(ray_resume_i);
      dut.ray_walk_i(ray_walk_i);
      dut.res_suspended_o(res_suspended_o);
      dut.res_walk_o(res_walk_o);
    }
  }
};

// rt_trav_wires: the signals between one unit and its side of the chip's
// testbench, named after the RTL ports they carry (common/rt_trav_ports.h).
template <class Unit>
class rt_trav_wires : public sc_core::sc_module,
                      public rt_trav_unit_ports<Unit, rt_signal, rt_signal>,
                      public rt_suspend_wires<Unit> {
 public:
  sc_core::sc_signal<typename Unit::cfg_t> cfg_i{Unit::kNames.cfgPort};

  explicit rt_trav_wires(sc_core::sc_module_name name) : sc_core::sc_module(name) {}

  // The node/cell port of a module whose C++ port names are the shared ones (node_*).
  template <class M>
  void bindNodePort(M& m) {
    lancer::sc::bindNodePort(m, *this);
  }
};

// rt_trav_bench: one implementation of a traversal unit (Dut: the unit's cycle
// model or its Verilated class; Unit: its traits, common/rt_trav_unit.h) as a
// chip of `units` copies, each on its own wires to the chip's testbench and
// memory (rt_trav_tb). The testbench's sides and the wires have the same port
// names, so one binding serves both and the DUT's common ports; the DUT's
// node/cell and configuration ports, whose C++ names are the unit's RTL
// names, are bound by Unit::bindUnitPorts. The binding below is the wiring
// diagram (traversal units <-> memory, rays in, results and visits out).
template <class Unit, class Dut>
class rt_trav_bench : public sc_core::sc_module {
 public:
  rt_trav_tb<Unit> u_tb;
  sc_core::sc_vector<rt_trav_wires<Unit>> wires;
  std::vector<std::unique_ptr<Dut>> duts;

  template <class... DutArgs>
  rt_trav_bench(sc_core::sc_module_name name, int units, DutArgs&&... args)
      : sc_core::sc_module(name), u_tb("u_tb", units), wires("unit", size_t(units)) {
    for (int u = 0; u < units; ++u) {
      rt_trav_wires<Unit>& w = wires[size_t(u)];
      auto& dut = *duts.emplace_back(std::make_unique<Dut>(("u_dut_" + std::to_string(u)).c_str(), args...));
      // The DUT: every port; the unit's own (configuration, node/cell port) by its traits.
      bindHostPorts(dut, w);
      bindMemPorts(dut, w);
      Unit::bindUnitPorts(dut, w);
      w.bindSuspendPorts(dut);
      // Its side of the testbench: clock, reset, configuration, streams, the memory side of the ports.
      rt_trav_side<Unit>& side = u_tb.sides[size_t(u)];
      bindHostPorts(side, w);
      side.cfg_i(w.cfg_i);
      lancer::sc::bindNodePort(side, w);
      bindMemPorts(side, w);
    }
  }
};

}  // namespace lancer::sc
