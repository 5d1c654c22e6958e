"""Running a study's `lancer` jobs, locally or as a Slurm job array, for the
study scripts (bench-chip, bench-structures): each job is one `lancer`
command line with a --report, under <out>/jobs/<key>.json, and a job with a
report is not run again (a study resumes where it stopped). The script's own
merge step turns the reports into its tables and plots; under Slurm it runs
as a job that depends on the array.
"""

import concurrent.futures
import json
import shlex
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def listed(text, kind=str):
    return [kind(v) for v in text.split(",") if v]


def add_executor_args(p, default_jobs=1):
    p.add_argument("--build", default="build", help="the build tree whose lancer runs the jobs")
    p.add_argument("--executor", default="local", choices=["local", "slurm"])
    p.add_argument("-j", "--jobs", type=int, default=default_jobs, help="local: jobs at once (each is single-threaded)")
    p.add_argument("--sbatch", default="", help="slurm: extra sbatch arguments")
    p.add_argument("--wait", action="store_true", help="slurm: wait for the merge job, exit with its status")
    p.add_argument("--merge-only", action="store_true")
    p.add_argument("--task", type=int, help="(a Slurm array task: the job to run)")


def scene_available(tool, name, scene, hint):
    if scene.startswith("builtin:") or (ROOT / scene).exists() or Path(scene).exists():
        return True
    print(f"{tool}: {name}: {scene} not found, skipped ({hint})", file=sys.stderr)
    return False


class Study:
    """One study's jobs under `out`: `tool` names it in messages and Slurm,
    `product` is the file its merge writes (the sign that a merge job ran)."""

    def __init__(self, tool, args, script, product):
        self.tool, self.args, self.script, self.product = tool, args, Path(script).resolve(), product
        self.out = Path(args.out)
        (self.out / "jobs").mkdir(parents=True, exist_ok=True)

    def report(self, job):
        return self.out / "jobs" / f"{job['key']}.json"

    def run_job(self, job):
        cmd = [str(Path(self.args.build) / "sw" / "lancer"), *job["args"], "--report", str(self.report(job))]
        start = time.monotonic()
        with open(self.out / "jobs" / f"{job['key']}.log", "w") as log:
            status = subprocess.run(cmd, cwd=ROOT, stdout=log, stderr=subprocess.STDOUT).returncode
        return status, time.monotonic() - start

    def run_local(self, jobs):
        todo = [j for j in jobs if not self.report(j).exists()]
        print(f"{self.tool}: {len(jobs)} jobs, {len(jobs) - len(todo)} with reports, {len(todo)} to run", flush=True)
        failed = 0
        with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, self.args.jobs)) as pool:
            futures = {pool.submit(self.run_job, j): j for j in todo}
            for done, future in enumerate(concurrent.futures.as_completed(futures), 1):
                job = futures[future]
                status, seconds = future.result()
                failed += status != 0
                what = "ok" if status == 0 else f"FAILED (exit {status}, {self.out}/jobs/{job['key']}.log)"
                print(f"{self.tool}: [{done}/{len(todo)}] {job['key']}: {what}, {seconds:.0f} s", flush=True)
        return failed

    def run_slurm(self, jobs):
        out = self.out.resolve()
        todo = [j for j in jobs if not self.report(j).exists()]
        (out / "jobs.json").write_text(json.dumps(jobs, indent=1))
        (out / "todo.txt").write_text("".join(j["key"] + "\n" for j in todo))
        me = ["/usr/bin/python3", str(self.script), "--out", str(out), "--build", str(Path(self.args.build).resolve())]
        extra = shlex.split(self.args.sbatch)
        merge_deps = []
        if todo:
            task = out / "array.sh"
            task.write_text("#!/bin/sh\nexec " + shlex.join(me) + " --task \"$SLURM_ARRAY_TASK_ID\"\n")
            task.chmod(0o755)
            array = subprocess.run(["sbatch", "--parsable", f"--job-name=lancer-{self.tool}", f"--array=0-{len(todo) - 1}",
                                    f"--output={out}/jobs/slurm-%a.out", *extra, str(task)], capture_output=True, text=True)
            if array.returncode != 0:
                sys.exit(f"{self.tool}: sbatch failed: {array.stderr.strip()}")
            merge_deps = [f"--dependency=afterany:{array.stdout.strip().split(';')[0]}"]
        merge = subprocess.run(["sbatch", "--parsable", f"--job-name=lancer-{self.tool}-merge", f"--output={out}/merge.out",
                                *merge_deps, *extra, "--wrap", shlex.join([*me, "--merge-only"])],
                               capture_output=True, text=True)
        if merge.returncode != 0:
            sys.exit(f"{self.tool}: sbatch of the merge failed: {merge.stderr.strip()}")
        merge_id = merge.stdout.strip().split(";")[0]
        print(f"{self.tool}: {len(todo)} jobs submitted as an array; the merge is job {merge_id} ({out}/merge.out)",
              flush=True)
        if not self.args.wait:
            return 0
        while subprocess.run(["squeue", "-h", "-j", merge_id], capture_output=True, text=True).stdout.strip():
            time.sleep(2)
        state = subprocess.run(["sacct", "-n", "-X", "-j", merge_id, "-o", "ExitCode"], capture_output=True, text=True)
        ok = (out / self.product).exists() and (state.returncode != 0 or state.stdout.strip() in ("", "0:0"))
        print(f"{self.tool}: the merge job ended ({'ok' if ok else 'failed: ' + str(out / 'merge.out')})")
        return 0 if ok else 1

    def run_task(self):
        jobs = {j["key"]: j for j in json.loads((self.out / "jobs.json").read_text())}
        key = (self.out / "todo.txt").read_text().split()[self.args.task]
        status, _ = self.run_job(jobs[key])
        return status

    def main(self, plan, merge):
        """The script's whole flow: a Slurm task, a merge, or plan, run and merge."""
        if self.args.task is not None:
            return self.run_task()
        jobs = plan(self.args)
        saved = self.out / "jobs.json"
        if self.args.merge_only:
            return merge(self.args, json.loads(saved.read_text()) if saved.exists() else jobs)
        saved.write_text(json.dumps(jobs, indent=1))
        if self.args.executor == "slurm":
            return self.run_slurm(jobs)
        failed = self.run_local(jobs)
        status = merge(self.args, jobs)
        return 1 if failed else status
