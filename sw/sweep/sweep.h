#pragma once

// `lancer sweep`: a study of what each bit of fixed-point precision costs and
// buys (docs/accuracy.md). The spec becomes a plan of jobs (width x unit x model
// x scene x ray set); the trees of the widths are built, optionally
// synthesized; the jobs missing a result run on an executor (local threads or
// Slurm job arrays); a merge gathers the results into sweep.csv, sweep.json,
// the summary table and the plots.

#include <string>
#include <vector>

#include "sweep/spec.h"

namespace lancer::sweep {

struct RunOptions {
  std::string out = "out/sweep";
  std::string executor = "local";        // local | slurm
  int jobs = 0;                          // local: jobs in parallel (0: the host's cores)
  std::vector<std::string> sbatchArgs;   // slurm: extra sbatch arguments (partition, time, ...)
  bool wait = false;                     // slurm: wait for the merge job
  bool plots = true;
};

// Runs the sweep; returns the exit status (0: every job has a result; 1: some
// job, build or scene failed, the rest kept). Throws InputError for a bad spec.
int runSweep(const Spec& spec, const RunOptions& options);

// A Slurm array task: the `task`-th key of `list` (one job key a line).
int runListedJob(const std::string& out, const std::string& list, int task);

}  // namespace lancer::sweep
