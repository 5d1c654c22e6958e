#!/usr/bin/env python3
"""lancer run over every scene of Debian's assimp-testmodels (docs/scenes.md).

Each file either traces (exit 0, a report with triangles, 0 mismatches against
the golden model) or is refused with exit 1 and one line, "lancer: error:
<file>: <reason>", the last on stderr. Never a crash, a hang (each run has a
timeout), or another exit. Which files are refused, and why, is pinned in
expected_refusals.txt ("<file>|<reason's start>"); every other file must trace.
Then a few files whose outcome the docs promise (formats and scene_numbers),
and malformed scenes made from the corpus: one line naming the file, exit 1.

  check_corpus.py LANCER MODELS WORKDIR [--update]

--update rewrites expected_refusals.txt from this run (review the diff).
"""
import json
import os
import subprocess
import sys
from pathlib import Path

TIMEOUT_S = 60
# Not scenes: pictures, texts and the buffers and materials other files name.
SKIPPED_SUFFIXES = {".png", ".jpg", ".jpeg", ".bmp", ".tga", ".dds", ".txt", ".md", ".bin", ".mtl", ".gz",
                    ".pcx", ".ktx", ".ktx2", ".tif", ".webp"}
REASON_CHARS = 60  # how much of a refusal's reason expected_refusals.txt pins

# Files whose outcome docs/scenes.md states: (file, scene_numbers, triangles or None).
PROMISED = [
    # Its buffers' floats placed by nodes whose numbers are decimal text.
    ("glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "correctly_rounded", 121496),
    ("BLEND/box.blend", "exact", None),
    ("BLEND/SuzanneSubdiv_252.blend", "exact", None),
    ("FBX/box.fbx", "exact", None),
    ("3DS/fels.3ds", "exact", None),
    ("Collada/duck.dae", "assimp_text", None),
    ("IFC/AC14-FZK-Haus.ifc", "assimp_text", None),
    ("X/test.x", "assimp_text", None),
    ("OBJ/box.obj", "correctly_rounded", 12),
]


def run(lancer, scene, workdir, cwd):
    report = Path(workdir) / "corpus_report.json"
    if report.exists():
        report.unlink()
    try:
        p = subprocess.run([lancer, "run", "--scene", scene, "--width", "16", "--height", "16", "--report", str(report)],
                           cwd=cwd, capture_output=True, text=True, errors="replace", timeout=TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return None, "", "", None
    data = json.loads(report.read_text()) if p.returncode == 0 and report.exists() else None
    return p.returncode, p.stdout, p.stderr, data


def refusal(scene, rc, stderr):
    """The reason of a proper refusal of `scene`, or None and what is wrong."""
    lines = [l for l in stderr.splitlines() if l and not l.startswith("warning:")]
    prefix = f"lancer: error: {scene}:"  # then a blank, or the line (OBJ, PLY, NFF)
    if rc != 1:
        return None, f"exit {rc}"
    if not lines or not lines[-1].startswith(prefix):
        return None, f"its last line does not start with '{prefix}': {lines[-1:]}"
    # Lancer's own lines: one. (assimp's OpenDDL parser prints a line of its
    # own before one OpenGEX refusal.)
    if sum(l.startswith("lancer:") for l in lines) != 1:
        return None, f"{len(lines)} lines: {lines}"
    return lines[-1][len(prefix):].lstrip(), ""


def main():
    lancer, models, workdir = sys.argv[1:4]
    update = "--update" in sys.argv[4:]
    expected_path = Path(__file__).with_name("expected_refusals.txt")
    expected = {}
    for line in expected_path.read_text().splitlines():
        if line and not line.startswith("#"):
            name, reason = line.split("|", 1)
            expected[name] = reason
    files = sorted(str(p.relative_to(models)) for p in Path(models).rglob("*")
                   if p.is_file() and p.suffix.lower() not in SKIPPED_SUFFIXES)
    failures, refused, traced = [], {}, 0
    for name in files:
        rc, stdout, stderr, report = run(lancer, name, workdir, models)
        if rc is None:
            failures.append(f"{name}: no answer in {TIMEOUT_S} s")
        elif rc == 0:
            traced += 1
            if not report or report.get("triangles", 0) <= 0:
                failures.append(f"{name}: exit 0 without a report of its triangles")
            elif "0 mismatches" not in stdout:
                failures.append(f"{name}: traced with mismatches against the golden model")
            elif name in expected and not update:
                failures.append(f"{name}: traced, but expected_refusals.txt says it is refused ({expected[name]})")
        else:
            reason, wrong = refusal(name, rc, stderr)
            if reason is None:
                failures.append(f"{name}: not a one-line refusal naming the file: {wrong}")
                continue
            refused[name] = reason[:REASON_CHARS]
            if update:
                continue
            if name not in expected:
                failures.append(f"{name}: refused, but expected to trace: {reason}")
            elif not reason.startswith(expected[name]):
                failures.append(f"{name}: refused for '{reason}', expected '{expected[name]}'")
    if update:
        header = [l for l in expected_path.read_text().splitlines() if l.startswith("#")]
        expected_path.write_text("\n".join(header + [f"{n}|{r}" for n, r in sorted(refused.items())]) + "\n")
        print(f"wrote {len(refused)} refusals to {expected_path}")
        return 0
    for name in expected:
        if name not in files:
            failures.append(f"{name}: listed in expected_refusals.txt, not in the corpus")

    # The outcomes the docs promise.
    for name, numbers, triangles in PROMISED:
        rc, stdout, stderr, report = run(lancer, name, workdir, models)
        if rc != 0 or not report:
            failures.append(f"{name}: expected to trace, exit {rc}: {stderr.strip()}")
            continue
        if report.get("scene_numbers") != numbers:
            failures.append(f"{name}: scene_numbers {report.get('scene_numbers')}, expected {numbers}")
        if triangles is not None and report.get("triangles") != triangles:
            failures.append(f"{name}: {report.get('triangles')} triangles, expected {triangles}")
        text_warning = any(l.startswith("warning:") and "may be a float off" in l for l in stderr.splitlines())
        if text_warning != (numbers == "assimp_text"):
            failures.append(f"{name}: the assimp_text warning is {'there' if text_warning else 'missing'}")

    # Malformed scenes: cut short, emptied, or bytes of another format.
    bad = Path(workdir) / "corpus_malformed"
    bad.mkdir(parents=True, exist_ok=True)
    cases = {
        "cut.blend": (Path(models) / "BLEND/box.blend").read_bytes()[:2000],
        "cut.dae": (Path(models) / "Collada/duck.dae").read_bytes()[:3000],
        "cut.fbx": (Path(models) / "FBX/box.fbx").read_bytes()[:500],
        "empty.3ds": b"",
        "text.ifc": b"this is not STEP\n",
        "noise.lwo": bytes(range(256)) * 4,
    }
    for file_name, content in cases.items():
        path = bad / file_name
        path.write_bytes(content)
        rc, _, stderr, _ = run(lancer, str(path), workdir, models)
        reason, wrong = refusal(str(path), rc, stderr) if rc is not None else (None, "no answer")
        if reason is None:
            failures.append(f"malformed {file_name}: not a one-line refusal naming the file: {wrong}")
    missing = bad / "missing.blend"
    rc, _, stderr, _ = run(lancer, str(missing), workdir, models)
    reason, wrong = refusal(str(missing), rc, stderr)
    if reason != "cannot open file":
        failures.append(f"missing.blend: expected 'cannot open file', got {reason or wrong}")

    print(f"{len(files)} files: {traced} traced with 0 mismatches, {len(refused)} refused with one line; "
          f"{len(PROMISED)} promised outcomes, {len(cases) + 1} malformed scenes")
    for f in failures:
        print("FAIL", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
