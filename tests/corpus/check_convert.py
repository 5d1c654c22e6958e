#!/usr/bin/env python3
"""lancer convert round trip: a scene converted to OBJ, PLY and glTF binary and
traced again gives the same hits, bit for bit.

For each scene: `lancer run --effects primary --hits` on the scene and on each
conversion, with one camera given in full (a converted scene carries no view),
and the hit lists (ray, triangle id, t, u, v and the golden model's raw
fixed-point fields) must be equal, byte for byte, and the run must report 0
mismatches. Then the errors: an unknown output format, an unwritable path.

  check_convert.py LANCER MODELS WORKDIR
"""
import subprocess
import sys
from pathlib import Path

SCENES = [
    ("builtin:cornell", "--eye 278,273,-800 --look-at 278,273,0"),
    ("glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "--eye 300,400,-900 --look-at 0,100,0"),
    ("BLEND/box.blend", "--eye 4,3,5 --look-at 0,0,0"),
    ("Collada/duck.dae", ""),  # no view: framed from its bounds, which the conversions keep
    ("IFC/AC14-FZK-Haus.ifc", "--eye 20,10,25 --look-at 5,2,-5"),
    ("STL/Spider_binary.stl", ""),
]
CAMERA = "--fov 40 --up 0,1,0 --width 48 --height 48"


def lancer(binary, *args):
    return subprocess.run([binary, *args], capture_output=True, text=True, timeout=300)


def main():
    binary, models, workdir = sys.argv[1:4]
    work = Path(workdir) / "convert"
    work.mkdir(parents=True, exist_ok=True)
    failures = []
    for scene, camera in SCENES:
        source = scene if scene.startswith("builtin:") else str(Path(models) / scene)
        stem = Path(scene).stem.replace(":", "_")
        view = (camera + " " + CAMERA).split()
        reference = work / f"{stem}.hits.csv"
        run = lancer(binary, "run", "--scene", source, "--effects", "primary", "--hits", str(reference), *view)
        if run.returncode != 0 or " 0 mismatches" not in run.stdout:
            failures.append(f"{scene}: lancer run failed: {run.stderr.strip()}")
            continue
        rows = reference.read_text().splitlines()[1:]
        hit = sum(row.split(",")[1] == "1" for row in rows)
        if hit == 0:
            failures.append(f"{scene}: the camera sees nothing; the check would be empty")
        for extension in ("obj", "ply", "glb"):
            converted = work / f"{stem}.{extension}"
            convert = lancer(binary, "convert", "--scene", source, "--out", str(converted))
            if convert.returncode != 0:
                failures.append(f"{scene} -> .{extension}: convert failed: {convert.stderr.strip()}")
                continue
            hits = work / f"{stem}.{extension}.hits.csv"
            again = lancer(binary, "run", "--scene", str(converted), "--effects", "primary", "--hits", str(hits), *view)
            if again.returncode != 0 or " 0 mismatches" not in again.stdout:
                failures.append(f"{scene} -> .{extension}: lancer run failed: {again.stderr.strip()}")
            elif hits.read_bytes() != reference.read_bytes():
                failures.append(f"{scene} -> .{extension}: the hits differ from the scene's ({hits} vs {reference})")
            else:
                print(f"{scene} -> .{extension}: the same hit list ({len(rows)} rays, {hit} hit)")
    for out, expected in ((work / "x.stl", "x.stl: '.stl' is not a format Lancer writes"),
                          (Path("/nonexistent/dir/x.ply"), "/nonexistent/dir/x.ply: cannot write file")):
        p = lancer(binary, "convert", "--scene", "builtin:cube", "--out", str(out))
        lines = p.stderr.strip().splitlines()
        if p.returncode != 1 or len(lines) != 1 or expected not in lines[0]:
            failures.append(f"convert to {out}: expected exit 1 and one line with '{expected}', got {p.returncode} {lines}")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
