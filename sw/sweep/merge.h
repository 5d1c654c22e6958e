#pragma once

// Gathers a sweep's job results into its outputs: sweep.json, sweep.csv, the
// deterministic columns alone in sweep-exact.csv (what the local and Slurm
// executors must agree on bit for bit), the summary table, and the plots
// (scripts/sweep-plot). Rows are per width, unit, model and scene, plus a
// scene "all" row per width, unit and model.

#include <cstdio>
#include <string>

namespace lancer::sweep {

struct MergeResult {
  size_t rows = 0;
  size_t missing = 0;  // planned jobs without a result (failed or not run)
  size_t errors = 0;   // failed jobs, builds, syntheses, plots
};

// Reads <out>/plan.json, <out>/trees.json, <out>/synth.json and <out>/jobs/;
// prints the table to `table`. Throws InputError if there is no plan.
MergeResult mergeSweep(const std::string& out, FILE* table, bool plots);

}  // namespace lancer::sweep
