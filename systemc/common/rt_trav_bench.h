#pragma once

#include <utility>

#include <systemc>

#include "common/rt_trav_mem.h"
#include "common/rt_trav_ports.h"
#include "common/rt_trav_tb.h"
#include "common/rt_trav_unit.h"

namespace lancer::sc {

// rt_trav_bench: one implementation of a traversal unit (Dut: the unit's cycle
// model or its Verilated class; Unit: its traits, common/rt_trav_unit.h) with
// its testbench and its memory, on signals named after the RTL ports they
// carry (common/rt_trav_ports.h). The testbench and the memory have the same
// port names, so one binding serves both and the DUT's common ports; the DUT's node/cell and
// configuration ports, whose C++ names are the unit's RTL names, are bound by
// Unit::bindUnitPorts. The binding below is the wiring diagram (traversal unit
// <-> memory, rays in, results and visits out).
template <class Unit, class Dut>
class rt_trav_bench : public sc_core::sc_module,
                      public rt_trav_host_ports<Unit, rt_signal, rt_signal>,
                      public rt_trav_node_port<Unit, rt_signal, rt_signal>,
                      public rt_trav_mem_ports<Unit, rt_signal, rt_signal> {
 public:
  sc_core::sc_signal<typename Unit::cfg_t> cfg_i{Unit::kNames.cfgPort};

  rt_trav_tb<Unit> u_tb{"u_tb"};
  rt_trav_mem<Unit> u_mem{"u_mem"};
  Dut u_dut;

  template <class... DutArgs>
  explicit rt_trav_bench(sc_core::sc_module_name name, DutArgs&&... args)
      : sc_core::sc_module(name), u_dut("u_dut", std::forward<DutArgs>(args)...) {
    // The DUT: every port; the unit's own (configuration, node/cell port) by its traits.
    bindHostPorts(u_dut, *this);
    bindMemPorts(u_dut, *this);
    Unit::bindUnitPorts(u_dut, *this);

    // The memory: the three read ports.
    u_mem.clk_i(this->clk_i);
    bindMemPorts(u_mem, *this);
    lancer::sc::bindNodePort(u_mem, *this);

    // The testbench: clock, reset, configuration, streams; observes the memory ports.
    bindHostPorts(u_tb, *this);
    u_tb.cfg_i(cfg_i);
    bindMemPorts(u_tb, *this);
    lancer::sc::bindNodePort(u_tb, *this);
  }

  // The node/cell port of a module whose C++ port names are the shared ones (node_*).
  template <class M>
  void bindNodePort(M& m) {
    lancer::sc::bindNodePort(m, *this);
  }
};

}  // namespace lancer::sc
