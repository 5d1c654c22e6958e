"""What the synthesis flow knows of a unit: its sources, their hash, the gate
model's clock and the figures of one Yosys run. scripts/synth (the source
lists), scripts/sweep-synth (one run's figures) and scripts/clock-table (the
committed table of estimated clocks) all read it from here.

As a command:
  lancer_synth.py sources TOP           the files Yosys reads for TOP, one a line
  lancer_synth.py hash TOP              their SHA-256 (sources_sha256)
  lancer_synth.py cached TREE TOP       TREE's figures of TOP if they are current (exit 1 if not)
"""

import hashlib
import shutil
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# The gate model (docs/accuracy.md, "Clock: the gate model"): Yosys's generic
# cells are 2-input gates with no delay, so a clock is estimated from the
# longest path between flip-flops in gates.
GATE_DELAY_PS = 25.0         # one loaded 2-input gate of a 16 nm-class library (about 2 FO4)
REGISTER_OVERHEAD_PS = 60.0  # clock-to-q, setup and skew
GATE_MODEL = {"gate_delay_ps": GATE_DELAY_PS, "register_overhead_ps": REGISTER_OVERHEAD_PS,
              "formula": "f_max = 1 / (register_overhead_ps + logic_depth * gate_delay_ps)"}


def fmax_mhz(depth):
    return 1e6 / (REGISTER_OVERHEAD_PS + depth * GATE_DELAY_PS)


def _read_list(path):
    """The files of a source list (rtl/synth/TOP.f): paths relative to rtl/,
    '#' comments, and '-f other.f' lines that read another list in place."""
    files = []
    for raw in path.read_text().splitlines():
        line = raw.split("#", 1)[0].strip()
        if not line:
            continue
        if line.startswith("-f "):
            files += _read_list(path.parent / line[3:].strip())
        else:
            files.append(ROOT / "rtl" / line)
    return files


def module_sources(top):
    """The modules Yosys reads for TOP, in compile order (every module of rtl/
    for a top without a list)."""
    listed = ROOT / "rtl" / "synth" / f"{top}.f"
    if listed.exists():
        return _read_list(listed)
    return sorted(p for p in (ROOT / "rtl").rglob("*.sv") if not p.name.endswith("_pkg.sv"))


def unit_sources(top):
    """Everything a synthesis of TOP depends on besides the generated package:
    its modules, the headers they include (rtl/lib/*.svh) and its Yosys scripts."""
    synth = ROOT / "rtl" / "synth"
    extra = sorted((ROOT / "rtl" / "lib").glob("*.svh")) + sorted(synth.glob(f"{top}_*.ys"))
    return module_sources(top) + extra


def sources_sha256(top):
    """SHA-256 over each source's path (relative to the root) and content: the
    identity of the RTL a figure was measured on."""
    h = hashlib.sha256()
    for path in unit_sources(top):
        h.update(str(path.relative_to(ROOT)).encode() + b"\n")
        h.update(path.read_bytes())
    return h.hexdigest()


def file_sha256(path):
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def package_widths(pkg):
    """(POS_W, DIR_W) of a generated rt_pkg.sv."""
    text = Path(pkg).read_text()
    pos = re.search(r"POS_W\s*=\s*(\d+)", text)
    dirw = re.search(r"DIR_W\s*=\s*(\d+)", text)
    if not pos or not dirw:
        raise ValueError(f"{pkg}: no POS_W or DIR_W")
    return int(pos.group(1)), int(dirw.group(1))


def _instance(node):
    """The instance a node of `ltp -noff` lies in: "\\u_shell.u_exit.holds_o [3]"
    and "$flatten\\u_shell.\\u_exit.$abc$..." both give "u_shell.u_exit"."""
    node = node.split(" (via ", 1)[0].strip()
    if node.startswith("$flatten"):
        inst = node[len("$flatten"):].split(".$", 1)[0]
    elif node.startswith("$"):
        inst = ""  # a cell Yosys made in the top itself
    else:
        inst = re.sub(r"\s*\[\d+\]$", "", node).rsplit(".", 1)[0] if "." in node else ""
    return inst.replace("\\", "")


def critical_path(ltp_text):
    """The longest path of `ltp -noff` as the instances it runs through, in
    order, with the gates spent in each: [{"at": "u_shell.u_check_arb",
    "gates": 33}, ...]; the path starts at a flip-flop ("from") and ends at one ("to")."""
    steps = re.findall(r"^\s*(\d+|ff): (.*)$", ltp_text, re.M)
    if not steps:
        return []
    path = []
    for index, node in steps[1:]:
        if index == "ff":
            break
        at = _instance(node) or "(top)"
        if path and path[-1]["at"] == at:
            path[-1]["gates"] += 1
        else:
            path.append({"at": at, "gates": 1})
    first = steps[0][1].split(" (via ", 1)[0].strip().lstrip("\\")
    last = steps[-1][1].split(" (via ", 1)[0].strip().lstrip("\\")
    return [{"from": first}] + path + [{"to": last}]


def cached_figures(tree, top, silicon=True):
    """TREE's figures of TOP (TREE/synth/TOP/sweep-synth.json, scripts/sweep-synth)
    while they were made from TREE's package and this tree's RTL sources, by
    content; else None. With `silicon` (lancer sweep), where OpenSTA is
    installed they must include the silicon flow's; scripts/clock-table asks
    for the gate model's only. lancer sweep and scripts/clock-table reuse a
    synthesis only through this."""
    cache = Path(tree) / "synth" / top / "sweep-synth.json"
    pkg = Path(tree) / "generated" / "rtl" / "rt_pkg.sv"
    if not cache.exists() or not pkg.exists():
        return None
    try:
        fig = json.loads(cache.read_text())
    except json.JSONDecodeError:
        return None
    current = (isinstance(fig, dict) and "error" not in fig and "fmax_mhz" in fig
               and fig.get("pkg_sha256") == file_sha256(pkg) and fig.get("sources_sha256") == sources_sha256(top)
               # with OpenSTA installed, the figures include the silicon flow's (scripts/sweep-synth),
               # but for a tree without the hardware models, whose activity cannot be measured
               and ("silicon" in fig or not silicon or not shutil.which("sta")
                    or not has_hardware_models(tree)))
    return fig if current else None


def has_hardware_models(tree):
    """Whether TREE was built with the hardware models (LANCER_HW_MODELS, the
    default): only then can a Verilated run measure a unit's toggle rates,
    which the silicon flow's power needs."""
    return (Path(tree) / "rtl" / "lancer_fst_activity").exists()


def run_figures(work, top, pkg):
    """The figures of one `scripts/synth` run with LANCER_SYNTH_LTP=1 in WORK."""
    work = Path(work)
    stat = (work / "stat.txt").read_text()
    log = (work / "synth.log").read_text()
    ltp = (work / "ltp.txt").read_text()
    # The last "Number of cells" is the whole design's; flip-flops are the cells named *DFF*.
    cells = int(re.findall(r"Number of cells:\s+(\d+)", stat)[-1])
    marker = "=== design hierarchy ==="
    design = stat[stat.rfind(marker):] if marker in stat else stat
    ffs = sum(int(n) for _, n in re.findall(r"^\s+(\$_\w*DFF\w*)\s+(\d+)", design, re.M))
    paths = re.findall(r"Longest topological path in \S+ \(length=(\d+)\)", ltp)
    depth = max(int(n) for n in paths)
    cpu = re.findall(r"CPU: user ([0-9.]+)s system ([0-9.]+)s", log)
    pos, dirw = package_widths(pkg)
    return {"top": top, "pos_bits": pos, "dir_bits": dirw, "cells": cells, "flip_flops": ffs,
            "logic_depth": depth, "fmax_mhz": round(fmax_mhz(depth), 1), "gate_model": GATE_MODEL,
            "critical_path": critical_path(ltp),
            "cpu_seconds": float(cpu[-1][0]) + float(cpu[-1][1]) if cpu else None,
            "pkg_sha256": file_sha256(pkg), "sources_sha256": sources_sha256(top)}


def main(argv):
    if len(argv) == 3 and argv[1] == "sources":
        for path in module_sources(argv[2]):
            print(path)
        return 0
    if len(argv) == 3 and argv[1] == "hash":
        print(sources_sha256(argv[2]))
        return 0
    if len(argv) == 4 and argv[1] == "cached":
        fig = cached_figures(argv[2], argv[3])
        if fig is None:
            return 1
        print(json.dumps(fig))
        return 0
    print(__doc__.split("As a command:")[1].rstrip(), file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
