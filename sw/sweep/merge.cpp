#include "sweep/merge.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <utility>

#include <fmt/format.h>

#include "common/error.h"
#include "sweep/job.h"
#include "sweep/process.h"
#include "sweep/spec.h"

namespace lancer::sweep {

namespace fs = std::filesystem;

namespace {

// The sums over a group of job results (camera chunks, or several scenes).
struct Totals {
  uint64_t rays = 0, inLattice = 0, hit = 0, disagreements = 0, hitMiss = 0, prim = 0, compared = 0;
  double tErrMax = 0, tErrSum = 0;
  uint64_t arbHwCorrect = 0, arbHwTie = 0, arbHwWithin = 0, arbHwBeyond = 0, arbRefWrong = 0;
  uint64_t cycles = 0, tests = 0, quadricTests = 0, steps = 0, refNodes = 0, mismatches = 0;
  bool cycleAccurate = true, refComparable = true;
  double modelSeconds = 0;
  uint64_t crackRays = 0, crackMisses = 0, crackRefDiffers = 0, crackRejected = 0;
  int isectLatency = -1;
  size_t cameraJobs = 0, crackJobs = 0;

  void addCamera(const nlohmann::json& result) {
    const nlohmann::json& r = result.at("run");
    ++cameraJobs;
    rays += r.value("rays", uint64_t(0));
    inLattice += r.value("rays_in_lattice", uint64_t(0));
    hit += r.value("rays_hit", uint64_t(0));
    disagreements += r.value("reference_disagreements", uint64_t(0));
    hitMiss += r.value("reference_hit_miss_differs", uint64_t(0));
    prim += r.value("reference_prim_differs", uint64_t(0));
    const uint64_t c = r.value("reference_compared", uint64_t(0));
    compared += c;
    tErrMax = std::max(tErrMax, r.value("t_error_max_lattice_units", 0.0));
    tErrSum += r.value("t_error_mean_lattice_units", 0.0) * double(c);
    const nlohmann::json a = r.value("arbiter", nlohmann::json::object());
    const nlohmann::json hw = a.value("hardware", nlohmann::json::object());
    arbHwCorrect += hw.value("correct", uint64_t(0));
    arbHwTie += hw.value("tie", uint64_t(0));
    arbHwWithin += hw.value("within_bound", uint64_t(0));
    arbHwBeyond += hw.value("beyond_bound", uint64_t(0));
    arbRefWrong += a.value("reference", nlohmann::json::object()).value("wrong", uint64_t(0));
    cycles += r.value("cycles", uint64_t(0));
    tests += r.value("intersection_tests", uint64_t(0));
    quadricTests += r.value("quadric_tests", uint64_t(0));
    cycleAccurate = cycleAccurate && r.value("cycle_accurate", false);
    mismatches += r.value("mismatches", uint64_t(0));
    modelSeconds += r.value("model_seconds", 0.0);
    steps += r.value("voxel_steps", uint64_t(0)) + r.value("node_steps", uint64_t(0));
    if (result.contains("reference_trace") && result["reference_trace"].is_object()) {
      refNodes += result["reference_trace"].value("nodes_visited", uint64_t(0));
    } else {
      refComparable = false;
    }
  }
  void addCracks(const nlohmann::json& result) {
    const nlohmann::json& r = result.at("run");
    ++crackJobs;
    const uint64_t n = r.value("rays", uint64_t(0));
    crackRays += n;
    crackMisses += n - r.value("rays_hit", uint64_t(0));
    crackRefDiffers += r.value("reference_hit_miss_differs", uint64_t(0));
    const nlohmann::json c = result.value("cracks", nlohmann::json::object());
    crackRejected += c.value("rejected", uint64_t(0));
    isectLatency = c.value("isect_latency_cycles", isectLatency);
  }
  // The sums over several scenes (the scene "all").
  Totals& operator+=(const Totals& t) {
    rays += t.rays, inLattice += t.inLattice, hit += t.hit;
    disagreements += t.disagreements, hitMiss += t.hitMiss, prim += t.prim, compared += t.compared;
    tErrMax = std::max(tErrMax, t.tErrMax), tErrSum += t.tErrSum;
    arbHwCorrect += t.arbHwCorrect, arbHwTie += t.arbHwTie, arbHwWithin += t.arbHwWithin;
    arbHwBeyond += t.arbHwBeyond, arbRefWrong += t.arbRefWrong;
    cycles += t.cycles, tests += t.tests, quadricTests += t.quadricTests, steps += t.steps, refNodes += t.refNodes, mismatches += t.mismatches;
    cycleAccurate = cycleAccurate && t.cycleAccurate;
    refComparable = refComparable && t.refComparable;
    modelSeconds += t.modelSeconds;
    crackRays += t.crackRays, crackMisses += t.crackMisses, crackRefDiffers += t.crackRefDiffers;
    crackRejected += t.crackRejected;
    cameraJobs += t.cameraJobs, crackJobs += t.crackJobs;
    isectLatency = std::max(isectLatency, t.isectLatency);
    return *this;
  }
};

double ratio(double a, double b) { return b > 0 ? a / b : NAN; }

// A CSV/JSON cell: NaN is "not measured" (empty in CSV, null in JSON).
nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

struct Column {
  const char* name;
  bool exact;  // deterministic: the same on every machine and executor
};

const std::vector<Column>& columns() {
  static const std::vector<Column> cols{
      {"width", true}, {"pos_bits", true}, {"dir_bits", true}, {"unit", true}, {"model", true}, {"scene", true},
      {"rays", true}, {"rays_in_lattice", true}, {"disagreements", true}, {"hit_miss_differs", true},
      {"prim_differs", true}, {"misclassified_fraction", true}, {"t_error_max_lattice", true},
      {"t_error_mean_lattice", true}, {"t_error_max_relative", true}, {"t_error_mean_relative", true},
      {"arbiter_hw_correct", true}, {"arbiter_hw_tie", true}, {"arbiter_hw_within_bound", true},
      {"arbiter_hw_beyond_bound", true}, {"arbiter_ref_wrong", true}, {"crack_rays", true},
      {"cracks", true}, {"crack_ref_hit_miss_differs", true}, {"crack_rays_rejected", true},
      {"unit_steps", true}, {"reference_steps", true}, {"extra_steps_fraction", true},
      {"steps_vs_widest_fraction", true},
      {"mismatches_vs_golden", true}, {"isect_latency_cycles", true}, {"cycles", true},
      {"cycles_per_ray", true}, {"tests_per_cycle", true}, {"tests_per_ray", true}, {"quadric_tests_per_ray", true}, {"cells", true},
      {"flip_flops", true}, {"logic_depth", true}, {"fmax_mhz_est", true}, {"ns_per_ray_at_fmax", true},
      {"area_um2", true}, {"sta_fmax_mhz", true}, {"ns_per_ray_at_sta", true}, {"pj_per_ray", true},
      {"cells_x_ns_per_ray", true}, {"host_model_seconds", false}, {"host_rays_per_second", false},
      {"build_seconds", false}, {"synth_cpu_seconds", false}};
  return cols;
}

std::string csvCell(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_float()) return fmt::format("{:.9g}", v.get<double>());
  return v.dump();
}

// The errors the width trees and the syntheses recorded.
void collectBuildErrors(const nlohmann::json& trees, const nlohmann::json& synth, nlohmann::json& errors) {
  if (trees.is_object()) {
    for (const auto& [name, t] : trees.items()) {
      if (t.contains("error")) errors.push_back(t["error"]);
    }
  }
  if (synth.is_object()) {
    for (const auto& [name, tops] : synth.items()) {
      for (const auto& [top, s] : tops.items()) {
        if (s.contains("error")) errors.push_back(s["error"]);
      }
    }
  }
}

// (width, unit, model) -> per scene -> the sums of its jobs' results.
using Groups = std::map<std::tuple<Width, std::string, std::string>, std::map<int, Totals>>;

// Every finished job's result in its group; a missing or failed job, or one
// with answers beyond the hardware's bound, is an error.
Groups groupResults(const std::string& out, const Spec& spec, const nlohmann::json& plan, MergeResult& m,
                    nlohmann::json& errors, nlohmann::json& missing) {
  Groups groups;
  for (const nlohmann::json& jj : plan.at("jobs")) {
    const Job job = Job::fromJson(jj);
    if (!jobDone(out, spec, job)) {
      ++m.missing;
      missing.push_back(job.key);
      const nlohmann::json e = readJson(jobErrorPath(out, job));
      errors.push_back(e.is_object() ? e.value("error", job.describe(spec) + ": failed")
                                     : job.describe(spec) + ": no result (not run yet)");
      continue;
    }
    const nlohmann::json result = readJson(jobResultPath(out, job));
    // An answer beyond the hardware's bound fails the sweep as an error does.
    const nlohmann::json& run = result.value("run", nlohmann::json::object());
    if (const uint64_t beyond = run.value("arbiter", nlohmann::json::object())
                                    .value("hardware", nlohmann::json::object())
                                    .value("beyond_bound", uint64_t(0))) {
      errors.push_back(fmt::format("{}: {} answers beyond the hardware's lattice bound (report {}/jobs/{}/run.json)",
                                   job.describe(spec), beyond, out, job.key));
    }
    Totals& t = groups[{job.width, job.unit, job.model}][job.scene];
    job.set == "cracks" ? t.addCracks(result) : t.addCamera(result);
  }
  return groups;
}

// One row of the table: a width, unit, model and scene, with the synthesis
// figures of the unit at that width (`syn`) and the width's tree (`tree`).
nlohmann::json sweepRow(const Width& w, const std::string& unit, const std::string& model, const std::string& scene,
                        const Totals& t, const nlohmann::json& syn, const nlohmann::json& tree) {
  const double lattice = double((int64_t(1) << w.pos) - 1);
  const bool timed = t.cycleAccurate && t.cameraJobs > 0;
  const double cyclesPerRay = timed ? ratio(double(t.cycles), double(t.inLattice)) : NAN;
  const double depth = syn.value("logic_depth", NAN);
  const double fmax = syn.value("fmax_mhz", NAN);  // the gate model's (scripts/lancer_synth.py)
  const double nsPerRay = cyclesPerRay / fmax * 1e3;
  const double cells = syn.value("cells", NAN);
  // The silicon flow's figures (scripts/sweep-synth, docs/silicon.md): SKY130 area, STA clock, energy.
  const nlohmann::json si = syn.value("silicon", nlohmann::json::object());
  const double areaUm2 = si.value("cell_area_um2", NAN) + si.value("macro_area_um2", NAN);
  const double staMhz = si.value("sta_fmax_mhz", NAN);
  const double pjPerRay = si.value("pj_per_cycle", NAN) * cyclesPerRay;
  const double tErrMean = ratio(t.tErrSum, double(t.compared));
  const bool hasCamera = t.cameraJobs > 0;
  const bool walks = isTraversalUnit(unit);
  const auto ifCracks = [&](uint64_t v) { return t.crackJobs ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"width", w.name()}, {"pos_bits", w.pos}, {"dir_bits", w.dir}, {"unit", unit}, {"model", model},
          {"scene", scene}, {"rays", t.rays}, {"rays_in_lattice", t.inLattice},
          {"disagreements", t.disagreements}, {"hit_miss_differs", t.hitMiss}, {"prim_differs", t.prim},
          {"misclassified_fraction", hasCamera ? num(ratio(double(t.disagreements), double(t.rays))) : nullptr},
          {"t_error_max_lattice", hasCamera ? num(t.tErrMax) : nullptr},
          {"t_error_mean_lattice", num(tErrMean)},
          {"t_error_max_relative", hasCamera ? num(t.tErrMax / lattice) : nullptr},
          {"t_error_mean_relative", num(tErrMean / lattice)},
          {"arbiter_hw_correct", t.arbHwCorrect}, {"arbiter_hw_tie", t.arbHwTie},
          {"arbiter_hw_within_bound", t.arbHwWithin}, {"arbiter_hw_beyond_bound", t.arbHwBeyond},
          {"arbiter_ref_wrong", t.arbRefWrong},
          {"crack_rays", ifCracks(t.crackRays)}, {"cracks", ifCracks(t.crackMisses)},
          {"crack_ref_hit_miss_differs", ifCracks(t.crackRefDiffers)},
          {"crack_rays_rejected", ifCracks(t.crackRejected)},
          {"unit_steps", walks ? nlohmann::json(t.steps) : nullptr},
          {"reference_steps", walks && t.refComparable ? nlohmann::json(t.refNodes) : nullptr},
          {"extra_steps_fraction",
           walks && t.refComparable ? num(ratio(double(t.steps), double(t.refNodes)) - 1.0) : nullptr},
          {"mismatches_vs_golden", t.mismatches},
          {"isect_latency_cycles", t.isectLatency >= 0 ? nlohmann::json(t.isectLatency) : nullptr},
          {"cycles", timed ? nlohmann::json(t.cycles) : nullptr},
          {"cycles_per_ray", num(cyclesPerRay)},
          {"tests_per_cycle", timed ? num(ratio(double(t.tests), double(t.cycles))) : nullptr},
          {"tests_per_ray", num(ratio(double(t.tests), double(t.inLattice)))},
          {"quadric_tests_per_ray", num(ratio(double(t.quadricTests), double(t.inLattice)))},
          {"cells", num(cells)}, {"flip_flops", num(syn.value("flip_flops", NAN))},
          {"logic_depth", num(depth)}, {"fmax_mhz_est", num(fmax)}, {"ns_per_ray_at_fmax", num(nsPerRay)},
          {"cells_x_ns_per_ray", num(cells * nsPerRay)},
          {"area_um2", num(areaUm2)}, {"sta_fmax_mhz", num(staMhz)},
          {"ns_per_ray_at_sta", num(cyclesPerRay / staMhz * 1e3)}, {"pj_per_ray", num(pjPerRay)},
          {"host_model_seconds", t.modelSeconds},
          {"host_rays_per_second", num(ratio(double(t.inLattice), t.modelSeconds))},
          {"build_seconds", tree.value("build_seconds", nlohmann::json(nullptr))},
          {"synth_cpu_seconds", num(syn.value("cpu_seconds", NAN))}};
}

// The rows in spec order: per width, unit and model, each scene, and "all"
// where there are several.
std::vector<nlohmann::json> sweepRows(const Spec& spec, const Groups& groups, const nlohmann::json& trees,
                                      const nlohmann::json& synth) {
  std::vector<nlohmann::json> rows;
  for (const Width& w : spec.widths) {
    const nlohmann::json tree =
        trees.is_object() ? trees.value(w.name(), nlohmann::json::object()) : nlohmann::json::object();
    for (const std::string& unit : spec.units) {
      const std::string top = synthTopOf(unit);
      nlohmann::json syn = nlohmann::json::object();
      if (synth.is_object() && synth.contains(w.name()) && synth[w.name()].contains(top)) syn = synth[w.name()][top];
      for (const std::string& model : spec.models) {
        const auto g = groups.find({w, unit, model});
        if (g == groups.end()) continue;
        Totals all;
        for (const auto& [s, t] : g->second) {
          rows.push_back(sweepRow(w, unit, model, spec.scenes[size_t(s)], t, syn, tree));
          all += t;
        }
        if (g->second.size() > 1) rows.push_back(sweepRow(w, unit, model, "all", all, syn, tree));
      }
    }
  }
  return rows;
}

// The unit's own walk against itself at the widest width of the sweep (the
// same structure on the same lattice cube, so what differs is the narrower
// arithmetic's conservative stepping).
void addStepsVsWidest(std::vector<nlohmann::json>& rows) {
  for (nlohmann::json& row : rows) {
    row["steps_vs_widest_fraction"] = nullptr;
    if (row["unit_steps"].is_null()) continue;
    const nlohmann::json* widest = nullptr;
    for (const nlohmann::json& other : rows) {
      if (other["unit"] != row["unit"] || other["model"] != row["model"] || other["scene"] != row["scene"]) continue;
      const int bits = other["pos_bits"].get<int>() + other["dir_bits"].get<int>();
      if (!widest || bits > (*widest)["pos_bits"].get<int>() + (*widest)["dir_bits"].get<int>()) widest = &other;
    }
    const double base = double((*widest)["unit_steps"].get<uint64_t>());
    row["steps_vs_widest_fraction"] = num(ratio(double(row["unit_steps"].get<uint64_t>()), base) - 1.0);
  }
}

// sweep.csv (every column) and sweep-exact.csv (the deterministic ones).
void writeCsvFiles(const std::string& out, const std::vector<nlohmann::json>& rows) {
  std::string csv, exact;
  // One line of each file: the cells of every column, and of the exact ones.
  const auto addLine = [&](auto cellOf) {
    bool first = true, firstExact = true;
    for (const Column& c : columns()) {
      const std::string cell = cellOf(c);
      if (!std::exchange(first, false)) csv += ',';
      csv += cell;
      if (!c.exact) continue;
      if (!std::exchange(firstExact, false)) exact += ',';
      exact += cell;
    }
    csv += '\n';
    exact += '\n';
  };
  addLine([](const Column& c) { return std::string(c.name); });
  for (const nlohmann::json& row : rows) addLine([&](const Column& c) { return csvCell(row.at(c.name)); });
  writeAtomically(out + "/sweep.csv", csv);
  writeAtomically(out + "/sweep-exact.csv", exact);
}

// Whether a later model of the spec has a row for the same width, unit and scene.
bool hasLaterModel(const Spec& spec, const std::vector<nlohmann::json>& rows, const nlohmann::json& row) {
  const auto pos = [&](const nlohmann::json& r) {
    return std::find(spec.models.begin(), spec.models.end(), r["model"].get<std::string>()) - spec.models.begin();
  };
  return std::any_of(rows.begin(), rows.end(), [&](const nlohmann::json& other) {
    return &other != &row && other["width"] == row["width"] && other["unit"] == row["unit"] &&
           other["scene"] == row["scene"] && pos(other) > pos(row);
  });
}

// The terminal summary: per width, unit and scene, the most detailed model
// (the last in the spec that has results: rtl after golden).
void printTable(FILE* table, const Spec& spec, const std::vector<nlohmann::json>& rows) {
  constexpr const char* kLine =
      "{:<6} {:<6} {:<7} {:<14} {:>9} {:>10} {:>7} {:>7} {:>8} {:>7} {:>10} {:>7} {:>7} {:>9} {:>7}\n";
  fmt::print(table, fmt::runtime(kLine), "width", "unit", "model", "scene", "misclass", "t err max", "cracks",
             "extra", "cyc/ray", "tst/cyc", "um2", "STA MHz", "pJ/ray", "host r/s", "build");
  const auto fmtNum = [](const nlohmann::json& v, const char* f) {
    return v.is_null() ? std::string("-") : fmt::format(fmt::runtime(f), v.get<double>());
  };
  for (const nlohmann::json& row : rows) {
    if (hasLaterModel(spec, rows, row)) continue;
    std::string scene = fs::path(row["scene"].get<std::string>()).stem().string();
    if (scene.size() > 14) scene = scene.substr(0, 14);
    const nlohmann::json mis = row["misclassified_fraction"];
    fmt::print(table, fmt::runtime(kLine), row["width"].get<std::string>(), row["unit"].get<std::string>(),
               row["model"].get<std::string>(), scene,
               mis.is_null() ? "-" : fmt::format("{:.4f}%", 100 * mis.get<double>()),
               fmtNum(row["t_error_max_relative"], "{:.2e}"),
               row["cracks"].is_null()
                   ? "-"
                   : fmt::format("{}/{}", row["cracks"].get<uint64_t>(), row["crack_rays"].get<uint64_t>()),
               row["extra_steps_fraction"].is_null()
                   ? "-"
                   : fmt::format("{:+.1f}%", 100 * row["extra_steps_fraction"].get<double>()),
               fmtNum(row["cycles_per_ray"], "{:.2f}"), fmtNum(row["tests_per_cycle"], "{:.3f}"),
               fmtNum(row["area_um2"], "{:.0f}"), fmtNum(row["sta_fmax_mhz"], "{:.0f}"),
               fmtNum(row["pj_per_ray"], "{:.0f}"),
               fmtNum(row["host_rays_per_second"], "{:.0f}"), fmtNum(row["build_seconds"], "{:.0f}s"));
  }
}

// scripts/sweep-plot over the merged sweep; a failure is one of its errors.
void runPlots(const std::string& out, const Spec& spec, nlohmann::json& errors) {
  const std::string log = out + "/plots.log";
  std::ofstream(log, std::ios::trunc).close();
  if (const int rc = runLogged({spec.source + "/scripts/sweep-plot", out}, log); rc != 0) {
    errors.push_back(fmt::format("plots: scripts/sweep-plot exited {}: {} (log {})", rc, lastLine(log), log));
  }
}

}  // namespace

MergeResult mergeSweep(const std::string& out, FILE* table, bool plots) {
  const nlohmann::json plan = readJson(out + "/plan.json");
  if (!plan.is_object()) throw InputError(fmt::format("{}/plan.json: no sweep plan here (run lancer sweep first)", out));
  const Spec spec = Spec::fromJson(plan.at("spec"), out + "/plan.json");
  const nlohmann::json trees = readJson(out + "/trees.json");
  const nlohmann::json synth = readJson(out + "/synth.json");

  MergeResult m;
  nlohmann::json errors = nlohmann::json::array(), missing = nlohmann::json::array();
  collectBuildErrors(trees, synth, errors);
  const Groups groups = groupResults(out, spec, plan, m, errors, missing);
  std::vector<nlohmann::json> rows = sweepRows(spec, groups, trees, synth);
  addStepsVsWidest(rows);
  m.rows = rows.size();
  writeCsvFiles(out, rows);
  if (table) printTable(table, spec, rows);
  if (plots && !rows.empty()) runPlots(out, spec, errors);
  m.errors = errors.size();
  // (Each synthesis in `synth` names the gate model its clock came from.)
  const nlohmann::json doc = {{"spec", spec.toJson()}, {"rows", rows},     {"trees", trees}, {"synth", synth},
                              {"missing_jobs", missing}, {"errors", errors}};
  writeAtomically(out + "/sweep.json", doc.dump(2) + "\n");
  return m;
}

}  // namespace lancer::sweep
