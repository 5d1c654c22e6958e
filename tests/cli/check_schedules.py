#!/usr/bin/python3
"""Every schedule gives every ray the same answer (docs/scheduling.md): for each
traversal unit and model, the path tracer on the Cornell box under --schedule
fifo and sorted on a 4-unit chip draws byte-equal images, with the same rays,
hits, tests, steps and memory reads in every class, 0 mismatches, 0 beyond the bound and
0 self-hits; each report names its schedule, and the sorted one states its
sort's cost.

Usage: check_schedules.py LANCER OUT_DIR [MODEL ...]
"""

import filecmp
import json
import subprocess
import sys
from pathlib import Path

SAME = ("rays", "hits", "intersection_tests", "steps", "memory_reads", "node_bytes", "mismatches")


def run(lancer, out, unit, model, schedule):
    stem = out / f"{unit}-{model}-{schedule}"
    subprocess.run([lancer, "run", "--scene", "builtin:cornell", "--integrator", "path", "--spp", "2",
                    "--accel", unit, "--model", model, "--units", "4", "--memory", "hierarchy",
                    "--width", "24", "--height", "24", "--schedule", schedule,
                    "--image", f"{stem}.png", "--report", f"{stem}.json"],
                   check=True, stdout=subprocess.DEVNULL)
    return json.loads(Path(f"{stem}.json").read_text()), Path(f"{stem}.png")


def main():
    lancer, out = sys.argv[1], Path(sys.argv[2])
    models = sys.argv[3:] or ["golden", "rtl", "systemc"]
    out.mkdir(parents=True, exist_ok=True)
    failures = []
    for unit in ("grid", "octree", "bvh"):
        for model in models:
            (fifo, fifo_png), (srt, srt_png) = (run(lancer, out, unit, model, s) for s in ("fifo", "sorted"))
            where = f"{unit} {model}"
            if not filecmp.cmp(fifo_png, srt_png, shallow=False):
                failures.append(f"{where}: the images differ")
            for r, name in ((fifo, "fifo"), (srt, "sorted")):
                if r["mismatches"] or r["beyond_bound"] or r["self_hits"]:
                    failures.append(f"{where} {name}: mismatches/beyond/self-hits {r['mismatches']}/{r['beyond_bound']}/{r['self_hits']}")
                if model != "golden" and r.get("schedule") != name:
                    failures.append(f"{where} {name}: the report names schedule {r.get('schedule')}")
            if set(fifo["classes"]) != set(srt["classes"]):
                failures.append(f"{where}: classes {sorted(fifo['classes'])} against {sorted(srt['classes'])}")
                continue
            for cls, a in fifo["classes"].items():
                b = srt["classes"][cls]
                for key in SAME:
                    if a.get(key) != b.get(key):
                        failures.append(f"{where} {cls}: {key} {a.get(key)} under fifo, {b.get(key)} under sorted")
            if model != "golden":
                sort = srt.get("sort", {})
                if not (sort.get("rays", 0) > 0 and sort.get("chip_cycles_estimate", 0) > 0 and "host_seconds" in sort):
                    failures.append(f"{where}: the sorted report states no sort cost: {sort}")
    for f in failures:
        print(f"check_schedules: {f}", file=sys.stderr)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
