#!/usr/bin/python3
"""Every schedule gives every ray the same answer (docs/scheduling.md): for each
traversal unit and model, the path tracer on the Cornell box under --schedule
fifo and sorted on a 4-unit chip draws byte-equal images, with the same rays,
hits, tests, steps and memory reads in every class, 0 mismatches, 0 beyond the bound and
0 self-hits; each report names its schedule, and the sorted one states its
sort's cost. The BVH runs on a treelet layout of 2-node blocks and the octree
on one of single child groups, and under --schedule treelet as well where the
model sets walks aside (TREELET_MODELS): the same answers, its walks suspended
and resumed through the ray queues (the report's ray_queues). Where a unit or
a model cannot, treelet is refused with a one-line error naming why.

Usage: check_schedules.py LANCER OUT_DIR [MODEL ...]
"""

import filecmp
import json
import subprocess
import sys
from pathlib import Path

SAME = ("rays", "hits", "intersection_tests", "steps", "memory_reads", "node_bytes", "mismatches")


# The models of each unit that set walks aside.
TREELET_MODELS = {"bvh": ("golden", "systemc", "rtl"), "octree": ("golden", "systemc", "rtl")}
LAYOUTS = {"bvh": ["--bvh-treelet-bytes", "62"], "octree": ["--octree-treelet-bytes", "64"]}


def command(lancer, out, unit, model, schedule):
    stem = out / f"{unit}-{model}-{schedule}"
    layout = LAYOUTS.get(unit, [])
    return stem, [lancer, "run", "--scene", "builtin:cornell", "--integrator", "path", "--spp", "2",
                  "--accel", unit, "--model", model, "--units", "4", "--memory", "hierarchy",
                  "--width", "24", "--height", "24", "--schedule", schedule, *layout,
                  "--image", f"{stem}.png", "--report", f"{stem}.json"]


def run(lancer, out, unit, model, schedule):
    stem, argv = command(lancer, out, unit, model, schedule)
    subprocess.run(argv, check=True, stdout=subprocess.DEVNULL)
    return json.loads(Path(f"{stem}.json").read_text()), Path(f"{stem}.png")


def refused(lancer, out, unit, model):
    """The error of --schedule treelet where it cannot run, or None if it ran."""
    _, argv = command(lancer, out, unit, model, "treelet")
    p = subprocess.run(argv, capture_output=True, text=True)
    return p.stderr.strip() if p.returncode == 1 else None


def main():
    lancer, out = sys.argv[1], Path(sys.argv[2])
    models = sys.argv[3:] or ["golden", "rtl", "systemc"]
    out.mkdir(parents=True, exist_ok=True)
    failures = []
    for unit in ("grid", "octree", "bvh"):
        for model in models:
            where = f"{unit} {model}"
            schedules = ["fifo", "sorted"]
            if model in TREELET_MODELS.get(unit, ()):
                schedules.append("treelet")
            else:
                error = refused(lancer, out, unit, model)
                expected = ("no ray queues" if unit != "grid" and model in ("systemc-pins", "rtl-systemc")
                            else "cannot set walks aside")
                if error is None or "error: --schedule treelet" not in error or expected not in error or "\n" in error:
                    failures.append(f"{where}: --schedule treelet is not refused with a clear error: {error!r}")
            runs = {s: run(lancer, out, unit, model, s) for s in schedules}
            fifo, fifo_png = runs["fifo"]
            for name, (r, png) in runs.items():
                if not filecmp.cmp(fifo_png, png, shallow=False):
                    failures.append(f"{where}: the {name} image differs from fifo's")
                if r["mismatches"] or r["beyond_bound"] or r["self_hits"]:
                    failures.append(f"{where} {name}: mismatches/beyond/self-hits {r['mismatches']}/{r['beyond_bound']}/{r['self_hits']}")
                if model != "golden" and r.get("schedule") != name:
                    failures.append(f"{where} {name}: the report names schedule {r.get('schedule')}")
                if set(fifo["classes"]) != set(r["classes"]):
                    failures.append(f"{where}: classes {sorted(fifo['classes'])} against {name}'s {sorted(r['classes'])}")
                    continue
                for cls, a in fifo["classes"].items():
                    b = r["classes"][cls]
                    for key in SAME:
                        if a.get(key) != b.get(key):
                            failures.append(f"{where} {cls}: {key} {a.get(key)} under fifo, {b.get(key)} under {name}")
            if model != "golden":
                sort = runs["sorted"][0].get("sort", {})
                if not (sort.get("rays", 0) > 0 and sort.get("chip_cycles_estimate", 0) > 0 and "host_seconds" in sort):
                    failures.append(f"{where}: the sorted report states no sort cost: {sort}")
            if "treelet" in runs and model != "golden":
                queues = runs["treelet"][0].get("ray_queues", {})
                if not queues.get("stats", {}).get("suspensions", 0) > 0:
                    failures.append(f"{where}: under treelet no walk was set aside: {queues}")
    for f in failures:
        print(f"check_schedules: {f}", file=sys.stderr)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
