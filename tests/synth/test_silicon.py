"""The silicon flow's pieces on small hand-made inputs (scripts/lancer_silicon.py):
the netlist reader's refusals, fan-out buffering, the power view, the names
activity is matched by, the memories of a Yosys dump, the clock a macro's
asynchronous read sets, and the link check naming the cells."""

import sys
import unittest
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
import lancer_silicon as si  # noqa: E402

PINS = {
    "sky130_fd_sc_hd__inv_1": {"in": ["A"], "out": ["Y"], "area": 3.75, "ff": False},
    "sky130_fd_sc_hd__buf_8": {"in": ["A"], "out": ["X"], "area": 11.26, "ff": False},
    "sky130_fd_sc_hd__dfxtp_1": {"in": ["CLK", "D"], "out": ["Q"], "area": 20.02, "ff": True},
}


def netlist_text(loads):
    cells = "\n".join(f"  sky130_fd_sc_hd__inv_1 _{k}_ (\n    .A(\\r_q[0] ),\n    .Y(o_{k})\n  );"
                      for k in range(loads))
    outs = "".join(f"  output o_{k};\n" for k in range(loads))
    return f"""module top(clk_i, d_i, {', '.join(f'o_{k}' for k in range(loads))});
  input clk_i;
  input d_i;
{outs}  wire \\r_q[0] ;
  sky130_fd_sc_hd__dfxtp_1 _ff_ (
    .CLK(clk_i),
    .D(d_i),
    .Q(\\r_q[0] )
  );
{cells}
endmodule
"""


class NetlistTest(unittest.TestCase):
    def test_reads_cells_ports_and_escaped_names(self):
        n = si.Netlist(netlist_text(3))
        self.assertEqual(n.top, "top")
        self.assertEqual(n.inputs, ["clk_i", "d_i"])
        self.assertEqual(len(n.instances), 4)
        self.assertEqual(n.instances[0][2]["Q"], "\\r_q[0]")

    def test_refuses_assigns_and_concatenations(self):
        with self.assertRaisesRegex(si.FlowError, "assign"):
            si.Netlist(netlist_text(1).replace("endmodule", "  assign o_0 = d_i;\nendmodule"))
        with self.assertRaisesRegex(si.FlowError, "constant or concatenation"):
            si.Netlist(netlist_text(1).replace(".D(d_i)", ".D(1'h0)"))

    def test_fanout_is_buffered_to_the_limit(self):
        n = si.Netlist(netlist_text(100))
        added = si.buffer_fanout(n, PINS)
        self.assertGreater(added, 0)
        fanout = {}
        for cell, _, pins in n.instances:
            for pin, net in pins.items():
                if pin in PINS[cell]["in"]:
                    fanout[net] = fanout.get(net, 0) + 1
        self.assertLessEqual(max(fanout.values()), si.MAX_FANOUT)
        # the written netlist reads back with the same cells
        self.assertEqual(len(si.Netlist(n.text()).instances), len(n.instances))

    def test_power_view_drives_register_loads_from_a_port(self):
        view, registers = si.power_view(si.Netlist(netlist_text(2)), PINS)
        self.assertEqual(list(registers.values()), ["\\r_q[0]"])
        port = next(iter(registers))
        self.assertIn(port, view.inputs)
        loads = [p["A"] for c, _, p in view.instances if c.endswith("inv_1")]
        self.assertEqual(loads, [port, port])


class NamesTest(unittest.TestCase):
    def test_netlist_and_fst_names_meet(self):
        self.assertEqual(si.signal_base("u_shell.g_cmp[0].old_hi_q_3_"), "u_shell.g_cmp.old_hi_q")
        self.assertEqual(si.signal_base("\\u_slots.mirror_q[5]_2_ "), "u_slots.mirror_q")
        self.assertEqual(si.signal_base("u_slots.mirror_q(5)"), "u_slots.mirror_q")

    def test_port_activity_matches_registers_and_defaults_the_rest(self):
        view, registers = si.power_view(si.Netlist(netlist_text(1)), PINS)
        activity = {"cycles": 10, "signals": {"TOP.top.r_q": {"per_bit_per_cycle": 0.25},
                                              "TOP.d_i": {"per_bit_per_cycle": 0.5}}}
        rates, counts = si.port_activity(view, registers, activity, "top")
        self.assertEqual(rates[next(iter(registers))], 0.25)
        self.assertEqual(rates["d_i"], 0.5)
        self.assertEqual(counts["registers_measured"], 1)
        self.assertEqual(counts["default"], 0.25)


DUMP = r"""
  cell $mem_v2 \u_slots.stack_q
    parameter \ABITS 9
    parameter \RD_CLK_ENABLE 3'010
    parameter \RD_PORTS 3
    parameter \SIZE 512
    parameter \WIDTH 35
    parameter \WR_PORTS 1
  end
"""


class MacroTest(unittest.TestCase):
    def test_memories_of_a_dump(self):
        m = si.parse_memories(DUMP)["u_slots.stack_q"]
        self.assertEqual((m["words"], m["width"], m["read_ports"], m["write_ports"], m["sync_reads"]),
                         (512, 35, 3, 1, 1))
        self.assertEqual(m["sync"], [False, True, False])

    def test_an_asynchronous_read_is_one_path_through_the_array(self):
        groups = {"reg2reg": {"delay_ns": 3.0, "from": "a", "to": "b"},
                  "macro:m:rd0:to_addr": {"delay_ns": 2.0, "from": "p", "to": "m.macro_rd_addr_0_"},
                  "macro:m:rd0:from_data": {"delay_ns": 1.5, "from": "m.macro_rd_data_0_", "to": "q"},
                  "macro:m:rd1:to_addr": {"delay_ns": 2.5, "from": "p", "to": "m.macro_rd_addr_5_"},
                  "macro:m:rd1:from_data": {"delay_ns": 0.5, "from": "m.macro_rd_data_9_", "to": "q"}}
        macros = {"m": {"read_ports": 2, "sync": [False, True],
                        "model": {"access_time_ns": 1.0, "cycle_time_ns": 1.2}}}
        period, path = si.clock_period(groups, macros)
        self.assertAlmostEqual(period, 4.5)  # port 0: 2.0 + 1.0 + 1.5; port 1 is synchronous: 1.0 + 0.5
        self.assertEqual((path["kind"], path["port"]), ("macro read (asynchronous)", 0))
        macros["m"]["sync"] = [True, True]
        period, path = si.clock_period(groups, macros)
        self.assertAlmostEqual(period, 3.0)  # synchronous: access + 1.5 < 3.0

    def test_ports_are_told_apart_by_bit(self):
        text = netlist_text(1).replace("input d_i;", "input d_i;\n  input \\m.macro_rd_data_0_ ;\n"
                                       "  input \\m.macro_rd_data_9_ ;\n  output \\m.macro_rd_addr_5_ ;")
        ports = si.macro_ports(si.Netlist(text), {"m": {"width": 8, "abits": 3}})["m"]
        self.assertEqual(sorted(ports["rd_data"]), [0, 1])
        self.assertEqual(sorted(ports["rd_addr"]), [1])

    def test_a_small_many_ported_array_stays_flip_flops(self):
        pins = {"sky130_fd_sc_hd__dfxtp_1": {"area": 20.02}, "sky130_fd_sc_hd__mux2_1": {"area": 11.26}}
        mems = {"best": {"words": 32, "width": 312, "read_ports": 3, "write_ports": 2, "sync": [True, True, False]},
                "stack": {"words": 1024, "width": 88, "read_ports": 1, "write_ports": 1, "sync": [False]},
                "tiny": {"words": 4, "width": 8, "read_ports": 1, "write_ports": 1, "sync": [True]},
                "counts": {"words": 64, "width": 32, "read_ports": 1, "write_ports": 1, "sync": [False]},
                "den": {"words": 32, "width": 69, "read_ports": 1, "write_ports": 1, "sync": [True]}}
        choice = si.choose_macros(mems, pins, None)
        self.assertFalse(choice["best"]["macro"])
        self.assertTrue(choice["stack"]["macro"])
        self.assertTrue(choice["den"]["macro"])
        self.assertNotIn("tiny", choice)
        self.assertNotIn("counts", choice)  # read in the cycle and under 4 Kbit: a register file

    def test_replicated_ports_cost_banks(self):
        one = si.price_macro({"words": 512, "width": 35, "read_ports": 1, "write_ports": 1})
        three = si.price_macro({"words": 512, "width": 35, "read_ports": 3, "write_ports": 1})
        self.assertEqual(three["banks"], 3)
        self.assertAlmostEqual(three["area_mm2"], 3 * one["area_mm2"])
        self.assertAlmostEqual(three["write_energy_pj"], 3 * one["write_energy_pj"])


class LinkTest(unittest.TestCase):
    def test_unlinked_cells_are_named(self):
        log = "Warning: netlist.v line 12, module sky130_fd_sc_hd__dlxtp_1 not found.\n"
        with self.assertRaisesRegex(si.FlowError, "dlxtp_1"):
            si.check_linked(log, "work")
        si.check_linked("Startpoint: a\n", "work")


if __name__ == "__main__":
    unittest.main()
