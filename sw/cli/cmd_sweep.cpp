// lancer sweep: what accuracy costs in time, over fixed-point widths
// (docs/accuracy.md). Also the commands its executors run: sweep-job (one job,
// e.g. a Slurm array task), sweep-merge (gather the results) and crack-rays
// (run in each width's own tree: rays exact on that width's lattice).
#include <filesystem>
#include <fstream>
#include <memory>

#include <fmt/format.h>

#include "cli/options.h"
#include "common/error.h"
#include "driver/quantize.h"
#include "golden/formats.h"
#include "scene/rays_file.h"
#include "driver/cracks.h"
#include "sweep/merge.h"
#include "sweep/sweep.h"

namespace lancer::cli {

namespace {

struct SweepArgs {
  std::string specFile;
  std::vector<std::string> widths, scenes, units, models, trees, cmakeArgs;
  sweep::Spec spec;
  sweep::RunOptions run;
  bool noPlots = false;
};

// The spec: the file's, then every option given on the command line over it.
sweep::Spec resolveSpec(const SweepArgs& a, const CLI::App& cmd) {
  sweep::Spec s;
  if (!a.specFile.empty()) {
    std::ifstream in(a.specFile);
    if (!in) throw InputError(fmt::format("--spec {}: cannot read", a.specFile));
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(fmt::format("--spec {}: not JSON: {}", a.specFile, e.what()));
    }
    s = sweep::Spec::fromJson(j, a.specFile);
  }
  const auto given = [&](const char* name) { return cmd.count(name) > 0; };
  if (given("--widths")) {
    s.widths.clear();
    for (const std::string& w : a.widths) s.widths.push_back(sweep::parseWidth(w, "--widths"));
  }
  if (given("--scenes")) s.scenes = a.scenes;
  // Scene files by absolute path: the jobs (Slurm tasks too) may run elsewhere.
  for (std::string& scene : s.scenes) {
    if (scene.rfind("builtin:", 0) != 0) scene = std::filesystem::absolute(scene).lexically_normal().string();
  }
  if (given("--units")) s.units = a.units;
  if (given("--models")) s.models = a.models;
  if (given("--image")) s.image = a.spec.image;
  if (given("--chunks")) s.chunks = a.spec.chunks;
  if (given("--crack-rays")) s.crackRays = a.spec.crackRays;
  if (given("--seed")) s.seed = a.spec.seed;
  if (given("--grid-res")) s.gridRes = a.spec.gridRes;
  if (given("--mem-latency")) s.memLatency = a.spec.memLatency;
  if (given("--clock-mhz")) s.clockMhz = a.spec.clockMhz;
  if (given("--synth")) s.synth = true;
  if (given("--synth-units")) s.synthUnits = a.spec.synthUnits;
  if (given("--source")) s.source = a.spec.source;
  if (given("--tree-pattern")) s.treePattern = a.spec.treePattern;
  if (given("--build-jobs")) s.buildJobs = a.spec.buildJobs;
  if (given("--cmake-arg")) s.cmakeArgs = a.cmakeArgs;
  for (const std::string& t : a.trees) s.addTree(t);
  s.resolvePaths();
  return s;
}

void addSweep(CLI::App& app) {
  auto a = std::make_shared<SweepArgs>();
  CLI::App* cmd = app.add_subcommand("sweep", "Accuracy, area, clock and time over fixed-point widths");
  cmd->add_option("--spec", a->specFile, "JSON sweep spec (options given here override it)");
  cmd->add_option("--widths", a->widths, "Widths P/D (or P for P/P), 4..24, e.g. 8/8,10/10,16/16")->delimiter(',');
  cmd->add_option("--scenes", a->scenes, "Scenes (files or builtin:cornell)")->delimiter(',');
  cmd->add_option("--units", a->units, "Units: isect (host BVH + pipeline), quadric (rt_quadric on the scenes' native "
                 "spheres and cones), grid, octree, bvh (default isect)")->delimiter(',');
  cmd->add_option("--models", a->models, "Models (default golden,rtl)")->delimiter(',');
  cmd->add_option("--image", a->spec.image, "Camera rays: IMAGE x IMAGE, auto-framed")->capture_default_str();
  cmd->add_option("--chunks", a->spec.chunks, "Split each scene's camera rays into this many jobs")->capture_default_str();
  cmd->add_option("--crack-rays", a->spec.crackRays, "Crack rays per width and scene (0: none)")->capture_default_str();
  cmd->add_option("--seed", a->spec.seed, "Seed of the crack rays")->capture_default_str();
  cmd->add_option("--grid-res", a->spec.gridRes, "Grid cells a side (default: the unit's heuristic)");
  cmd->add_option("--mem-latency", a->spec.memLatency, "Memory latency of the traversal units")->capture_default_str();
  cmd->add_option_function<double>(
      "--clock-mhz", [a](double mhz) { a->spec.clockMhz = mhz; },
      "Clock of the simulated rates in the run reports (default: each run's estimated clock, rtl/synth/clocks.json)");
  cmd->add_flag("--synth", a->spec.synth, "Synthesize each width's units with Yosys (slow; cached per tree)");
  cmd->add_option("--synth-units", a->spec.synthUnits, "With --synth, only these units (rt_grid and rt_octree take "
                                                      "minutes and GBs each)")
      ->delimiter(',');
  cmd->add_option("--source", a->spec.source, "Lancer source tree to configure the width trees from")
      ->default_str(LANCER_SOURCE_DIR);
  cmd->add_option("--tree-pattern", a->spec.treePattern, "Where a width's tree goes: {pos} and {dir} are replaced "
                                                          "(default <source>/build-sweep/{pos}-{dir})");
  cmd->add_option("--tree", a->trees, "Use an existing tree for a width: WIDTH=DIR (repeatable)");
  cmd->add_option("--cmake-arg", a->cmakeArgs, "Extra configure argument of new trees (repeatable)");
  cmd->add_option("--build-jobs", a->spec.buildJobs, "Parallel compile jobs per tree build")->capture_default_str();
  cmd->add_option("--out", a->run.out, "Output folder")->capture_default_str();
  cmd->add_option("--executor", a->run.executor, "local (threads on this host) or slurm (sbatch --array)")
      ->capture_default_str();
  cmd->add_option("--jobs,-j", a->run.jobs, "Local executor: jobs in parallel (default: the host's cores)");
  cmd->add_option("--sbatch-arg", a->run.sbatchArgs, "Slurm: extra sbatch argument (repeatable), e.g. --partition=x");
  cmd->add_flag("--wait", a->run.wait, "Slurm: wait for the merge job and print the table");
  cmd->add_flag("--no-plots", a->noPlots, "Skip the PNG plots");
  cmd->callback([a, cmd] {
    a->run.plots = !a->noPlots;
    const int status = sweep::runSweep(resolveSpec(*a, *cmd), a->run);
    if (status) throw CheckFailed("some jobs of the sweep have no result (errors above; rerun to resume)");
  });
}

void addSweepJob(CLI::App& app) {
  struct Args {
    std::string out, list;
    int task = -1;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("sweep-job", "Run one job of a planned sweep (what a Slurm array task runs)");
  cmd->add_option("--out", a->out, "The sweep's output folder")->required();
  cmd->add_option("--list", a->list, "File of job keys, one a line")->required();
  cmd->add_option("--task", a->task, "Line of the list to run, from 0 (SLURM_ARRAY_TASK_ID)")->required();
  cmd->callback([a] {
    if (sweep::runListedJob(a->out, a->list, a->task)) throw CheckFailed(fmt::format("task {} failed", a->task));
  });
}

void addSweepMerge(CLI::App& app) {
  struct Args {
    std::string out;
    bool noPlots = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("sweep-merge", "Gather a sweep's job results into sweep.csv, sweep.json and plots");
  cmd->add_option("--out", a->out, "The sweep's output folder")->required();
  cmd->add_flag("--no-plots", a->noPlots, "Skip the PNG plots");
  cmd->callback([a] {
    const sweep::MergeResult m = sweep::mergeSweep(a->out, stdout, !a->noPlots);
    if (m.missing || m.errors) {
      throw CheckFailed(fmt::format("{} jobs without a result, {} errors (see {}/sweep.json)", m.missing, m.errors, a->out));
    }
  });
}

void addCrackRays(CLI::App& app) {
  struct Args {
    SceneOptions scene;
    size_t count = 1024;
    uint64_t seed = 1;
    std::string out, report;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "crack-rays", "Rays exactly through shared edges and vertices on this build's lattice (docs/accuracy.md)");
  a->scene.quadrics = QuadricForm::Tessellate;  // cracks are at shared triangle edges
  a->scene.add(*cmd);
  cmd->add_option("--count", a->count, "Rays, about half at edges and half at vertices")->capture_default_str();
  cmd->add_option("--seed", a->seed, "Seed of the choice")->capture_default_str();
  cmd->add_option("--out", a->out, "Rays file to write")->required();
  cmd->add_option("--report", a->report, "JSON report file");
  cmd->callback([a] {
    const Scene scene = a->scene.load();
    const Quantizer quantizer(scene.bounds);
    const CrackRays c = makeCrackRays(scene, quantizer, a->count, a->seed);
    writeRaysFile(a->out, c.rays,
                  fmt::format("{}: {} crack rays ({} at edges, {} at vertices) on the {}/{}-bit lattice, seed {}",
                              scene.name, c.rays.size(), c.edgeRays, c.vertexRays, fx::kPosBits, fx::kDirBits,
                              a->seed));
    fmt::print("crack-rays: {} ({} triangles): {} rays ({} at shared edges of {}, {} at closed vertices of {}), "
               "{} rejected, formats {}/{}\n",
               scene.name, scene.size(), c.rays.size(), c.edgeRays, c.sharedEdges, c.vertexRays, c.closedVertices,
               c.rejected, fx::kPosBits, fx::kDirBits);
    if (c.rays.empty()) throw InputError(fmt::format("{}: no shared edge or closed vertex to aim at", scene.name));
    writeReport(a->report, {{"command", "crack-rays"}, {"scene", scene.name}, {"scene_numbers", toString(scene.numbers)}, {"triangles", scene.size()},
                            {"rays", c.rays.size()}, {"edge_rays", c.edgeRays}, {"vertex_rays", c.vertexRays},
                            {"shared_edges", c.sharedEdges}, {"closed_vertices", c.closedVertices},
                            {"rejected", c.rejected}, {"seed", a->seed}, {"pos_bits", fx::kPosBits},
                            {"dir_bits", fx::kDirBits}, {"isect_latency_cycles", fx::kIsectLatency}});
  });
}

}  // namespace

void addSweepCommand(CLI::App& app) {
  addSweep(app);
  addSweepJob(app);
  addSweepMerge(app);
  addCrackRays(app);
}

}  // namespace lancer::cli
