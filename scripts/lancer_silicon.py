"""The silicon flow (docs/silicon.md): a unit mapped by Yosys onto SkyWater's
SKY130 high-density standard cells, its large arrays cut out as memory macros
priced by the CACTI table (rtl/synth/sram/sram.json), its high fan-out nets
buffered, timed by OpenSTA, and its power at the STA clock from the toggle
rates of a Verilated run. scripts/silicon runs it; scripts/clock-table writes
its figures into rtl/synth/clocks.json.

Every constant of the flow is here, so a figure states what it was made with.
"""

import functools
import gzip
import hashlib
import importlib.machinery
import importlib.util
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SYNTH = ROOT / "rtl" / "synth"
# LANCER_SILICON_LIBERTY names another copy (the bad-input test points it nowhere).
LIBERTY = Path(os.environ.get("LANCER_SILICON_LIBERTY", SYNTH / "liberty" / "sky130_fd_sc_hd__tt_025C_1v80.lib.gz"))
MACRO_CUT = SYNTH / "silicon_macro_cut.v"
SRAM_TABLE = SYNTH / "sram" / "sram.json"
LIBRARY = {"name": "sky130_fd_sc_hd", "corner": "tt_025C_1v80", "node_nm": 130, "vdd_v": 1.8,
           "file": "rtl/synth/liberty/sky130_fd_sc_hd__tt_025C_1v80.lib.gz"}
CLOCK_SOURCE = f"sta {LIBRARY['name']} {LIBRARY['corner']}"

# Cells a synthesis should not pick: low-power and isolation cells, probes,
# delay and clock-tree cells, diodes, fill, tap, tie, tristates, latches, scan
# and set/reset flip-flops. ABC of Yosys 0.23 has no -dont_use, so they are left
# out of a copy of the library used for mapping; timing reads the whole library.
DONT_USE = re.compile(r"__(lpflow_|probe|clkdly|dlygate|dlymetal|clkbuf|clkinv|diode|decap|fill|tap|conb|"
                      r"ebufn|einv|macro_|dl|sdf|sedf|dfbb|bufbuf|bufinv|sdlclkp)")

# An array becomes a memory macro when it holds at least this many bits and has
# at most this many read and write ports (the per-slot state that every slot's
# logic reads at once stays flip-flops: it is a register file by nature). An
# array read asynchronously (its address computed in the cycle it is read)
# needs MACRO_MIN_BITS_ASYNC: below that it is a flip-flop register file, whose
# read ABC folds into the address logic (the grid's 64 x 32 cell-queue counts
# set a 79 MHz clock as macros, on a path of 7.8 ns to their address). The
# macro must also be smaller than the flip-flops (choose_macros).
MACRO_MIN_BITS = 2048
MACRO_MIN_BITS_ASYNC = 4096
MACRO_MAX_READ_PORTS = 4
MACRO_MAX_WRITE_PORTS = 2

# ABC's delay target (ps) for map/upsize/dnsize; the figures come from STA, this
# only steers the mapping.
ABC_DELAY_PS = 8000
ABC_SCRIPT = f"""strash
dretime
map -D {ABC_DELAY_PS}
cleanup
buffer -p -c
upsize -c -D {ABC_DELAY_PS}
dnsize -c -D {ABC_DELAY_PS}
"""

# Fan-out repair (what a placer's buffering would do): a net with more loads
# than this gets a tree of buffers, each driving at most this many.
MAX_FANOUT = 12
FANOUT_BUFFER = ("sky130_fd_sc_hd__buf_8", "A", "X")
TIE_CELL = "sky130_fd_sc_hd__conb_1"
WIRE_LOAD = "Small"  # the library's default wire-load model (all its models are the same)
STA_PERIOD_NS = 100.0  # the clock timing is run at: slack on it gives each path's delay


class FlowError(Exception):
    """A failure of the flow a user can act on; the message says what and how."""


def tool(name, package):
    path = shutil.which(name)
    if not path:
        raise FlowError(f"silicon: no `{name}` on PATH: install the Debian package {package} "
                        f"(scripts/deps installs it)")
    return path


def check_inputs():
    if not LIBERTY.exists():
        raise FlowError(f"silicon: no liberty file {LIBERTY}: it is committed with the "
                        f"project (SkyWater SKY130, rtl/synth/liberty/README.md); restore it with git checkout")
    if not SRAM_TABLE.exists():
        raise FlowError(f"silicon: no memory table {SRAM_TABLE.relative_to(ROOT)} (rtl/synth/sram/README.md)")
    tool("yosys", "yosys")
    tool("sta", "opensta")


def flow_sha256():
    """The identity of the flow: every setting that shapes a figure (the cells
    left out, the macro policy, ABC's script, the buffering, the wire load,
    the vectorless activity), the macro cut, the libraries and the memory
    table. Editing the code around them does not change it."""
    settings = json.dumps({"dont_use": DONT_USE.pattern, "macro": [MACRO_MIN_BITS, MACRO_MIN_BITS_ASYNC,
                                                                   MACRO_MAX_READ_PORTS, MACRO_MAX_WRITE_PORTS],
                           "abc": ABC_SCRIPT, "fanout": [MAX_FANOUT, *FANOUT_BUFFER], "tie": TIE_CELL,
                           "wire_load": WIRE_LOAD, "vectorless": VECTORLESS_ACTIVITY, "yosys": YOSYS_STEPS},
                          sort_keys=True)
    h = hashlib.sha256(settings.encode())
    for path in (MACRO_CUT, LIBERTY, SRAM_TABLE):
        h.update(path.name.encode() + b"\n" + path.read_bytes())
    return h.hexdigest()


# ---- Libraries ----------------------------------------------------------------------

def _cells(text):
    """(name, start, end) of every cell group of a liberty text, by brace matching."""
    for m in re.finditer(r'\n\s*cell\s*\(\s*"?([A-Za-z0-9_]+)"?\s*\)\s*\{', text):
        depth, j = 0, m.end() - 1
        while True:
            c = text[j]
            if c == "{":
                depth += 1
            elif c == "}":
                depth -= 1
                if depth == 0:
                    break
            j += 1
        yield m.group(1), m.start(), j + 1


def write_libraries(work):
    """The whole library (for timing) and the mapping copy without DONT_USE cells,
    unpacked into WORK once; returns (timing, mapping) paths."""
    work = Path(work)
    timing, mapping = work / "sky130_hd_tt.lib", work / "sky130_hd_tt_map.lib"
    if timing.exists() and mapping.exists():
        return timing, mapping
    text = gzip.open(LIBERTY, "rt").read()
    kept, pos = [], 0
    for name, start, end in _cells(text):
        kept.append(text[pos:start])
        if not DONT_USE.search(name):
            kept.append(text[start:end])
        pos = end
    kept.append(text[pos:])
    timing.write_text(text)
    mapping.write_text("".join(kept))
    return timing, mapping


def cell_pins(liberty_path):
    """{cell: {"in": [...], "out": [...], "area": µm², "ff": bool}} of a liberty file."""
    text = Path(liberty_path).read_text()
    cells = {}
    for name, start, end in _cells(text):
        body = text[start:end]
        pins = {"in": [], "out": []}
        for pm in re.finditer(r'\bpin\s*\(\s*"?(\w+)"?\s*\)\s*\{', body):
            seg = body[pm.end():pm.end() + 400]
            d = re.search(r"direction\s*:\s*\"?(\w+)", seg)
            if d and d.group(1) in ("input", "output"):
                pins["in" if d.group(1) == "input" else "out"].append(pm.group(1))
        area = re.search(r"\barea\s*:\s*([0-9.]+)", body)
        cells[name] = {**pins, "area": float(area.group(1)) if area else 0.0, "ff": bool(re.search(r"\bff\s*\(", body))}
    return cells


# ---- Yosys ----------------------------------------------------------------------------

# Two Yosys runs with a decision between them. The first reads the sources
# and runs generic synthesis up to the memories, which it lists; the flow then
# chooses the arrays that become macros (choose_macros); the second cuts those
# out (each becomes ports of the top: read data in; addresses, enables and
# write data out), finishes synthesis, maps flip-flops and logic onto cells,
# ties constants, makes every port and net one bit (this OpenSTA reads no
# concatenated assigns) and writes the netlist.
YOSYS_ELAB = """synth -top {top} -flatten -run :fine
tee -q -o memories.txt dump t:$mem_v2
write_rtlil coarse.il
"""
YOSYS_CUT = """techmap -map {macro_cut} {cells}
expose -input w:*.macro_rd_data
expose w:*.macro_rd_addr w:*.macro_rd_en w:*.macro_wr_addr w:*.macro_wr_en w:*.macro_wr_data
"""
YOSYS_MAP = """read_rtlil coarse.il
{cut}synth -top {top} -flatten -run fine:
dfflibmap -liberty {lib}
abc -liberty {lib} -script abc.script
opt_clean -purge
setundef -zero
hilomap -singleton -hicell {tie} HI -locell {tie} LO
splitnets -ports -format __
splitnets -format __
insbuf -buf sky130_fd_sc_hd__buf_2 A X
opt_clean -purge
tee -q -o stat.txt stat -liberty {lib}
write_verilog -noattr -noexpr -nohex -nodec netlist_mapped.v
"""
YOSYS_STEPS = YOSYS_ELAB + YOSYS_CUT + YOSYS_MAP  # the flow's identity (flow_sha256)


def elab_script(top, pkg, modules, chparams=""):
    """TOP's sources read (the package first, rtl/lib for includes), its
    parameters set, then YOSYS_ELAB."""
    return (f"read_verilog -sv -I{ROOT / 'rtl' / 'lib'} {pkg} {' '.join(str(m) for m in modules)}\n{chparams}"
            + YOSYS_ELAB.format(top=top))


def map_script(top, macros, mapping_lib):
    cut = YOSYS_CUT.format(macro_cut=MACRO_CUT, cells=" ".join(f"{top}/{name}" for name in sorted(macros))) \
        if macros else ""
    return YOSYS_MAP.format(top=top, cut=cut, lib=mapping_lib, tie=TIE_CELL)


def flop_array_um2(mem, pins):
    """What an array costs as flip-flops: a flip-flop a bit with a multiplexer a
    write port in front, and a (words:1) multiplexer tree a read port and bit."""
    ff = pins["sky130_fd_sc_hd__dfxtp_1"]["area"]
    mux = pins["sky130_fd_sc_hd__mux2_1"]["area"]
    bits = mem["words"] * mem["width"]
    return bits * (ff + mem["write_ports"] * mux) + mem["read_ports"] * mem["width"] * (mem["words"] - 1) * mux


def choose_macros(memories, pins, table):
    """The arrays that become memory macros: at least MACRO_MIN_BITS, at most
    MACRO_MAX_READ/WRITE_PORTS, and smaller as a macro (CACTI) than as flip-flops
    (a small array with many ports is a register file of flip-flops on a real
    chip too). {name: {flop_um2, macro_um2}} of every candidate, with "macro" set."""
    choice = {}
    for name, mem in memories.items():
        least = MACRO_MIN_BITS if all(mem["sync"]) else MACRO_MIN_BITS_ASYNC
        if mem["words"] * mem["width"] < least or mem["read_ports"] > MACRO_MAX_READ_PORTS \
                or mem["write_ports"] > MACRO_MAX_WRITE_PORTS:
            continue
        flops = flop_array_um2(mem, pins)
        macro = price_macro(mem, table)["area_mm2"] * 1e6
        choice[name] = {"flop_um2": round(flops), "macro_um2": round(macro), "macro": macro < flops}
    return choice


def parse_memories(dump_text):
    """The $mem_v2 cells of a Yosys dump: {name: {words, width, read_ports, write_ports, sync_reads}}."""
    mems = {}
    for block in re.split(r"\n\s*cell \$mem_v2 ", dump_text)[1:]:
        name = block.split(None, 1)[0].lstrip("\\")
        params = dict(re.findall(r"parameter \\(\w+) (\S+)", block))

        def num(key):
            v = params[key]
            return int(v.split("'")[1], 2) if "'" in v else int(v)

        rd = num("RD_PORTS")
        clk_en = params.get("RD_CLK_ENABLE", "0")
        bits = (clk_en.split("'")[1] if "'" in clk_en else bin(int(clk_en))[2:]).rjust(rd, "0")
        mems[name] = {"words": num("SIZE"), "width": num("WIDTH"), "abits": num("ABITS"), "read_ports": rd,
                      "write_ports": num("WR_PORTS"), "sync_reads": bits.count("1"),
                      # read port k is synchronous when bit k (from the right) of RD_CLK_ENABLE is set
                      "sync": [bits[-1 - k] == "1" for k in range(rd)]}
    return mems


# ---- The netlist ----------------------------------------------------------------------

class Netlist:
    """A flat Yosys netlist of library cells: ports, and instances with their pin
    connections. Written back whole (no assigns, one bit a net)."""

    def __init__(self, text):
        m = re.search(r"\bmodule\s+(\S+)\s*\(", text)
        if not m:
            raise FlowError("silicon: no module in the netlist")
        self.top = m.group(1)
        body = text[m.end():]
        if re.search(r"^\s*assign\b", body, re.M):
            line = re.search(r"^\s*assign\b.*$", body, re.M).group(0).strip()
            raise FlowError(f"silicon: the netlist has an assign ({line}): it must be cells only")
        self.inputs, self.outputs = [], []
        for kind, name in re.findall(r"^\s*(input|output)\s+(?:\[[^\]]*\]\s*)?(\\\S+ |\w+)\s*;", body, re.M):
            (self.inputs if kind == "input" else self.outputs).append(name.strip())
        self.instances = []  # [cell type, instance name, {pin: net}]
        for cm in re.finditer(r"^\s*(\w+)\s+(\\\S+ |\w+)\s*\(\s*((?:\.\w+\((?:\\\S+ |[^()\s]*)\s*\),?\s*)*)\);", body, re.M):
            pins = {p: n.strip() for p, n in re.findall(r"\.(\w+)\(\s*(\\\S+ |[^()\s]*)\s*\)", cm.group(3))}
            self.instances.append([cm.group(1), cm.group(2).strip(), pins])
        for net in (n for _, _, pins in self.instances for n in pins.values()):
            if "{" in net or "'" in net:
                raise FlowError(f"silicon: the netlist connects a constant or concatenation ({net})")

    def cell_types(self):
        return {t for t, _, _ in self.instances}

    def text(self):
        nets = set(self.inputs) | set(self.outputs)
        for _, _, pins in self.instances:
            nets.update(n for n in pins.values() if n)
        ports = self.inputs + self.outputs
        out = [f"module {self.top} ({', '.join(_esc(p) for p in ports)});"]
        out += [f"  input {_esc(p)};" for p in self.inputs]
        out += [f"  output {_esc(p)};" for p in self.outputs]
        out += [f"  wire {_esc(n)};" for n in sorted(nets - set(ports))]
        for cell, name, pins in self.instances:
            conns = ", ".join(f".{p}({_esc(n)})" for p, n in pins.items() if n)
            out.append(f"  {cell} {_esc(name)} ({conns});")
        out.append("endmodule")
        return "\n".join(out) + "\n"


def _esc(name):
    name = name.strip()
    if re.fullmatch(r"[A-Za-z_][A-Za-z0-9_]*", name):
        return name
    return (name if name.startswith("\\") else "\\" + name) + " "


def buffer_fanout(netlist, pins, clock="clk_i"):
    """Buffer trees on every net with more than MAX_FANOUT cell inputs (the clock
    is ideal in STA and left alone). Returns the buffers added."""
    loads = {}
    for inst in netlist.instances:
        cell, _, conns = inst
        for pin, net in conns.items():
            if net and pin in pins[cell]["in"] and net != clock:
                loads.setdefault(net, []).append((inst, pin))
    buf_cell, buf_in, buf_out = FANOUT_BUFFER
    added = 0
    for net, sinks in loads.items():
        level = 0
        while len(sinks) > MAX_FANOUT:
            groups = [sinks[i:i + MAX_FANOUT] for i in range(0, len(sinks), MAX_FANOUT)]
            sinks = []
            for group in groups:
                added += 1
                new_net = f"fanout_{added}_{level}"
                for inst, pin in group:
                    inst[2][pin] = new_net
                buf = [buf_cell, f"fanout_buf_{added}", {buf_in: net, buf_out: new_net}]
                netlist.instances.append(buf)
                sinks.append((buf, buf_in))
            level += 1
    return added


def power_view(netlist, pins):
    """A copy of the netlist for power: every flip-flop's output drives a new
    input port instead (this OpenSTA propagates activity from input ports only,
    and ignores activity set on internal pins), so the registers' measured
    toggle rates can be set on those ports. Returns (netlist, {port: register net})."""
    view = Netlist.__new__(Netlist)
    view.top, view.inputs, view.outputs = netlist.top, list(netlist.inputs), list(netlist.outputs)
    view.instances = [[c, n, dict(p)] for c, n, p in netlist.instances]
    registers = {}
    for k, (cell, name, conns) in enumerate(view.instances):
        if not pins[cell]["ff"]:
            continue
        for pin in pins[cell]["out"]:
            net = conns.get(pin)
            if not net:
                continue
            port = f"power_q_{k}_{pin}"
            registers[port] = net
            conns[pin] = f"power_float_{k}_{pin}"  # the register's own pin now drives nothing
    # one pass to redirect every load of a register net to its port
    port_of = {net: port for port, net in registers.items()}
    for cell, name, conns in view.instances:
        for p, n in list(conns.items()):
            if n in port_of and p in pins[cell]["in"]:
                conns[p] = port_of[n]
    # a register net that is also an output port keeps the name, driven through a buffer
    buf_cell, buf_in, buf_out = FANOUT_BUFFER
    for net, port in port_of.items():
        if net in view.outputs:
            view.instances.append([buf_cell, f"power_obuf_{port}", {buf_in: port, buf_out: net}])
    view.inputs += list(registers)
    return view, registers


# ---- OpenSTA ----------------------------------------------------------------------------

def _sta_header(timing_lib, netlist_path, top, period_ns):
    return f"""read_liberty {timing_lib}
read_verilog {netlist_path}
link_design {top}
set_wire_load_model -name {WIRE_LOAD}
create_clock -name clk -period {period_ns} [get_ports clk_i]
"""


def macro_ports(netlist, memories=None):
    """{memory: {"rd_data": {port: [...]}, "rd_addr": {port: [...]}, "out": [...]}} of the
    cut macros' ports; a read port's bits are told apart by their index (the
    cut concatenates the ports, port 0 lowest) when `memories` gives widths."""
    macros = {}
    for port in netlist.inputs + netlist.outputs:
        m = re.match(r"\\?(.+)\.macro_(rd_data|rd_addr|rd_en|wr_addr|wr_en|wr_data)(?:_(\d+)_)?$", port.strip())
        if not m:
            continue
        name, kind, bit = m.group(1), m.group(2), int(m.group(3) or 0)
        entry = macros.setdefault(name, {"rd_data": {}, "rd_addr": {}, "out": []})
        mem = (memories or {}).get(name)
        if kind == "rd_data":
            entry["rd_data"].setdefault(bit // mem["width"] if mem else 0, []).append(port)
        else:
            entry["out"].append(port)
            if kind == "rd_addr":
                entry["rd_addr"].setdefault(bit // mem["abits"] if mem else 0, []).append(port)
    return macros


def _tcl_ports(ports):
    return "[get_ports {" + " ".join(p.strip().lstrip("\\") for p in ports) + "}]"


def timing_script(timing_lib, netlist_path, netlist, memories, clock="clk_i"):
    """OpenSTA on a long clock, so each path group's worst slack gives its delay:
    flip-flop to flip-flop, the unit's own inputs and outputs (external delay 0),
    and for each memory macro the paths from each read port's data, to each
    read port's address, and to all its pins."""
    macros = macro_ports(netlist, memories)
    macro_set = {p for m in macros.values() for ports in m["rd_data"].values() for p in ports}
    macro_set |= {p for m in macros.values() for p in m["out"]}
    ins = [p for p in netlist.inputs if p != clock and p not in macro_set]
    outs = [p for p in netlist.outputs if p not in macro_set]
    s = _sta_header(timing_lib, netlist_path, netlist.top, STA_PERIOD_NS)
    all_in = [p for p in netlist.inputs if p != clock]
    if all_in:
        s += f"set_input_delay 0 -clock clk {_tcl_ports(all_in)}\n"
    if netlist.outputs:
        s += f"set_output_delay 0 -clock clk {_tcl_ports(netlist.outputs)}\n"
    s += "set regs_ck [all_registers -clock_pins]\nset regs_d [all_registers -data_pins]\n"
    groups = [("reg2reg", "-from $regs_ck -to $regs_d")]
    if ins:
        groups.append(("in2reg", f"-from {_tcl_ports(ins)} -to $regs_d"))
    if outs:
        groups.append(("reg2out", f"-from $regs_ck -to {_tcl_ports(outs)}"))
    if ins and outs:
        groups.append(("in2out", f"-from {_tcl_ports(ins)} -to {_tcl_ports(outs)}"))
    for name, ports in sorted(macros.items()):
        for k, data in sorted(ports["rd_data"].items()):
            groups.append((f"macro:{name}:rd{k}:from_data", f"-from {_tcl_ports(data)}"))
        for k, addr in sorted(ports["rd_addr"].items()):
            groups.append((f"macro:{name}:rd{k}:to_addr", f"-to {_tcl_ports(addr)}"))
        if ports["out"]:
            groups.append((f"macro:{name}:to_pins", f"-to {_tcl_ports(ports['out'])}"))
    for name, args in groups:
        s += f'puts "=== group {name}"\nreport_checks -path_delay max {args} -digits 4\n'
    return s


def parse_timing(report, netlist):
    """{group: {"delay_ns", "from", "to"}} of timing_script's report (a group with
    no path is absent); "from"/"to" name flip-flops by the register bit they hold."""
    q_net = {}
    for cell, name, conns in netlist.instances:
        if "Q" in conns:
            q_net[name] = conns["Q"]

    def readable(point):
        inst = point.split()[0].split("/")[0]
        return q_net.get(inst, inst).strip().lstrip("\\")

    groups = {}
    for chunk in report.split("=== group ")[1:]:
        name = chunk.split("\n", 1)[0].strip()
        slack = re.search(r"^\s*(-?[0-9.]+)\s+slack \((?:MET|VIOLATED)\)", chunk, re.M)
        start = re.search(r"^Startpoint: (.+)$", chunk, re.M)
        end = re.search(r"^Endpoint: (.+)$", chunk, re.M)
        if not slack:
            continue
        groups[name] = {"delay_ns": round(STA_PERIOD_NS - float(slack.group(1)), 4),
                        "from": readable(start.group(1)), "to": readable(end.group(1))}
    return groups


def clock_period(groups, macros):
    """The shortest clock period every path meets, and the path that sets it.
    A macro's synchronous read port delivers data its access time after the
    edge; an asynchronous one (a register file read in the cycle) lies on one
    path from its address logic through the array to its data's loads; a
    macro's input pins need its setup (taken as its cycle time less its access
    time, at least zero: CACTI gives no setup)."""
    candidates = []
    for name in ("reg2reg", "in2reg", "reg2out", "in2out"):
        if name in groups:
            g = groups[name]
            candidates.append((g["delay_ns"], {"kind": name, "from": g["from"], "to": g["to"]}))
    for name, m in macros.items():
        access = m["model"]["access_time_ns"]
        setup = max(0.0, m["model"]["cycle_time_ns"] - access)
        for k in range(m["read_ports"]):
            data = groups.get(f"macro:{name}:rd{k}:from_data")
            addr = groups.get(f"macro:{name}:rd{k}:to_addr")
            if not data:
                continue
            if not m["sync"][k] and addr:
                candidates.append((addr["delay_ns"] + access + data["delay_ns"],
                                   {"kind": "macro read (asynchronous)", "macro": name, "port": k,
                                    "from": addr["from"], "to": data["to"], "access_ns": access}))
            else:
                candidates.append((access + data["delay_ns"], {"kind": "macro read", "macro": name, "port": k,
                                                               "from": name, "to": data["to"], "access_ns": access}))
        pins = groups.get(f"macro:{name}:to_pins")
        if pins:
            candidates.append((pins["delay_ns"] + setup, {"kind": "macro input", "macro": name,
                                                          "from": pins["from"], "to": name}))
    delay, path = max(candidates, key=lambda c: c[0])
    return round(delay, 4), path


def power_script(timing_lib, netlist_path, top, period_ns, port_activity, default_activity):
    """report_power at the clock with every input port's activity (toggles per
    cycle) set, the measured ones one by one."""
    s = _sta_header(timing_lib, netlist_path, top, period_ns)
    # An input's activity is per cycle of its clock: without one, OpenSTA propagates nothing from it.
    s += "set_input_delay 0 -clock clk [delete_from_list [all_inputs] [get_ports clk_i]]\n"
    s += f"set_power_activity -input -activity {default_activity:.6f} -duty 0.5\n"
    for port, rate in sorted(port_activity.items()):
        s += f"sta::set_power_input_port_activity [get_ports {{{port.strip().lstrip(chr(92))}}}] {rate:.6f} 0.5\n"
    s += "report_power -digits 6\n"
    return s


def vectorless_script(timing_lib, netlist_path, top, period_ns, activity):
    s = _sta_header(timing_lib, netlist_path, top, period_ns)
    s += f"set_power_activity -global -activity {activity} -duty 0.5\nreport_power -digits 6\n"
    return s


def dynamic_w(power):
    """The dynamic part (internal + switching) of parse_power's figures."""
    return power["internal_w"] + power["switching_w"]


def parse_power(report):
    """{"internal_w", "switching_w", "leakage_w", "total_w"} of report_power's Total row."""
    m = re.search(r"^Total\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)", report, re.M)
    if not m:
        raise FlowError("silicon: report_power gave no Total row:\n" + report[-2000:])
    keys = ("internal_w", "switching_w", "leakage_w", "total_w")
    return {k: float(v) for k, v in zip(keys, m.groups())}


def run_sta(script, work, name):
    work = Path(work)
    (work / f"{name}.tcl").write_text(script)
    proc = subprocess.run([tool("sta", "opensta"), "-exit", str(work / f"{name}.tcl")], capture_output=True,
                          text=True)
    out = proc.stdout + proc.stderr
    (work / f"{name}.log").write_text(out)
    if proc.returncode != 0:
        raise FlowError(f"silicon: OpenSTA failed on {name} (log {work / (name + '.log')}):\n{out[-2000:]}")
    return out


def check_linked(log, work):
    """link_design must resolve every cell: an unmapped cell or a latch is an error naming it."""
    bad = re.findall(r"^(?:Warning|Error): .*(?:not found|unknown|undefined).*$", log, re.M | re.I)
    if bad:
        raise FlowError("silicon: the netlist does not link (" + str(work) + "):\n  " + "\n  ".join(bad[:20]))


# ---- Memories -------------------------------------------------------------------------

@functools.cache
def _cacti_table():
    """rtl/synth/sram/cacti-table as a module (its interpolation), loaded once."""
    loader = importlib.machinery.SourceFileLoader("cacti_table", str(SYNTH / "sram" / "cacti-table"))
    spec = importlib.util.spec_from_loader("cacti_table", loader)
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def price_macro(mem, table=None):
    """A memory macro's area, energy per access, leakage and timing from the
    CACTI table (1 read + 1 write port arrays, interpolated in words and width).
    More ports are built by replication, as multi-ported memories are from
    1R1W banks (LaForest and Steffan, "Efficient multi-ported memories for
    FPGAs", FPGA 2010): one bank per read port and write port pair, every
    write going to the banks of all read ports."""
    table = table or json.loads(SRAM_TABLE.read_text())
    one = _cacti_table().query(table, "sram", [mem["words"], mem["width"]])
    banks = max(1, mem["read_ports"]) * max(1, mem["write_ports"])
    energy, leakage = supply_scale(table)
    return {"banks": banks, "area_mm2": one["area_mm2"] * banks, "read_energy_pj": one["read_energy_pj"] * energy,
            "write_energy_pj": one["write_energy_pj"] * max(1, mem["read_ports"]) * energy,
            "leakage_mw": one["leakage_mw"] * banks * leakage, "access_time_ns": one["access_time_ns"],
            "cycle_time_ns": one["cycle_time_ns"], "method": one["method"]}


def supply_scale(table):
    """CACTI's interpolated supply is not the cells' 1.8 V: dynamic energy is
    scaled by the square of the ratio, leakage by the ratio (first order; the
    same in driver/silicon.cpp for the caches)."""
    ratio = LIBRARY["vdd_v"] / table["technology"]["vdd_v"]
    return ratio * ratio, ratio


def stat_figures(stat_text, pins):
    """Area (µm²), cells and flip-flops by kind of `stat -liberty`."""
    area = float(re.findall(r"Chip area for module .*?:\s*([0-9.]+)", stat_text)[-1])
    counts = {c: int(n) for c, n in re.findall(r"^\s+(sky130_fd_sc_hd__\w+)\s+(\d+)\s*$", stat_text, re.M)}
    ffs = {c: n for c, n in counts.items() if pins.get(c, {}).get("ff")}
    return {"area_um2": round(area, 1), "cells": sum(counts.values()), "flip_flops": sum(ffs.values()),
            "flip_flops_by_cell": ffs, "cells_by_kind": _by_kind(counts)}


def _by_kind(counts):
    kinds = {}
    for cell, n in counts.items():
        base = re.sub(r"_\d+$", "", cell.replace("sky130_fd_sc_hd__", ""))
        kind = ("flip-flop" if base.startswith("df") or base.startswith("edf") else
                "adder" if base in ("fa", "ha", "maj3") else
                "xor" if base.startswith("x") else
                "mux" if base.startswith("mux") else
                "buffer/inverter" if base in ("buf", "inv") else
                "tie" if base == "conb" else "logic")
        kinds[kind] = kinds.get(kind, 0) + n
    return kinds


# ---- Activity ---------------------------------------------------------------------------

# The vectorless figure shown beside the measured one: every net toggling in
# this share of cycles (OpenSTA's global activity, no propagation).
VECTORLESS_ACTIVITY = 0.1


def signal_base(name):
    """The name of a register or port without bit, word or generate indices, as
    both the netlist (splitnets' _N_ suffix, memory_map's [N]) and an FST
    (Verilator's [N] or (N)) spell it: "u_shell.g_cmp[0].old_hi_q_3_" -> "u_shell.g_cmp.old_hi_q"."""
    n = name.strip().lstrip("\\")
    n = re.sub(r"_\d+_$", "", n)
    return re.sub(r"\s*[\[(]\d+[\])]", "", n)


def port_activity(view, registers, activity, top):
    """Each input port's measured toggle rate (a register's port by the register
    it stands for) from lancer_fst_activity's entries, and how much was matched.
    Ports without a measurement get the bit-weighted mean of the registers that
    have one."""
    signals = {}
    for full, entry in activity["signals"].items():
        parts = full.split(".")
        # Verilator names the root scope after the top, and the top inside it: "rt_isect.rt_isect.det4_q"
        rest = parts[len(parts) - 1 - parts[::-1].index(top) + 1:] if top in parts else parts[1:]
        if rest:
            signals.setdefault(signal_base(".".join(rest)), entry)
    rates, reg_toggles = {}, 0.0
    inputs = [port for port in view.inputs if port != "clk_i" and port not in registers]
    counts = {"registers": len(registers), "registers_measured": 0, "inputs": len(inputs), "inputs_measured": 0}
    for port in inputs + list(registers):
        entry = signals.get(signal_base(registers.get(port, port)))
        if entry is None:
            continue
        rate = rates[port] = min(float(entry["per_bit_per_cycle"]), 1.0)
        if port in registers:
            counts["registers_measured"] += 1
            reg_toggles += rate
        else:
            counts["inputs_measured"] += 1
    measured = counts["registers_measured"]
    counts["default"] = round(reg_toggles / measured, 6) if measured else VECTORLESS_ACTIVITY
    counts["mean_register_activity"] = counts["default"]
    return rates, counts
