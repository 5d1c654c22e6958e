#include "sweep/merge.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

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
  uint64_t cycles = 0, tests = 0, steps = 0, refNodes = 0, mismatches = 0;
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
      {"cycles_per_ray", true}, {"tests_per_cycle", true}, {"tests_per_ray", true}, {"cells", true},
      {"flip_flops", true}, {"logic_depth", true}, {"fmax_mhz_est", true}, {"ns_per_ray_at_fmax", true},
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

}  // namespace

MergeResult mergeSweep(const std::string& out, FILE* table, bool plots) {
  const nlohmann::json plan = readJson(out + "/plan.json");
  if (!plan.is_object()) throw InputError(fmt::format("{}/plan.json: no sweep plan here (run lancer sweep first)", out));
  const Spec spec = Spec::fromJson(plan.at("spec"), out + "/plan.json");
  const nlohmann::json trees = readJson(out + "/trees.json");
  const nlohmann::json synth = readJson(out + "/synth.json");

  MergeResult m;
  nlohmann::json errors = nlohmann::json::array(), missing = nlohmann::json::array();
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
  // Group the results: (width, unit, model) -> per scene -> totals.
  std::map<std::tuple<Width, std::string, std::string>, std::map<int, Totals>> groups;
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

  std::vector<nlohmann::json> rows;
  for (const Width& w : spec.widths) {
    const nlohmann::json tree = trees.is_object() ? trees.value(w.name(), nlohmann::json::object()) : nlohmann::json::object();
    for (const std::string& unit : spec.units) {
      const std::string top = synthTopOf(unit);
      nlohmann::json syn = nlohmann::json::object();
      if (synth.is_object() && synth.contains(w.name()) && synth[w.name()].contains(top)) syn = synth[w.name()][top];
      for (const std::string& model : spec.models) {
        auto g = groups.find({w, unit, model});
        if (g == groups.end()) continue;
        Totals all;
        bool first = true;
        std::vector<std::pair<std::string, Totals>> scenes;
        for (const auto& [s, t] : g->second) scenes.push_back({spec.scenes[size_t(s)], t});
        // The scene "all": the sums over every scene with results.
        for (const auto& [name, t] : scenes) {
          all.rays += t.rays; all.inLattice += t.inLattice; all.hit += t.hit;
          all.disagreements += t.disagreements; all.hitMiss += t.hitMiss; all.prim += t.prim;
          all.compared += t.compared; all.tErrMax = std::max(all.tErrMax, t.tErrMax); all.tErrSum += t.tErrSum;
          all.arbHwCorrect += t.arbHwCorrect; all.arbHwTie += t.arbHwTie; all.arbHwWithin += t.arbHwWithin;
          all.arbHwBeyond += t.arbHwBeyond; all.arbRefWrong += t.arbRefWrong; all.cycles += t.cycles;
          all.tests += t.tests; all.steps += t.steps; all.refNodes += t.refNodes; all.mismatches += t.mismatches;
          all.cycleAccurate = all.cycleAccurate && t.cycleAccurate;
          all.refComparable = all.refComparable && t.refComparable;
          all.modelSeconds += t.modelSeconds; all.crackRays += t.crackRays; all.crackMisses += t.crackMisses;
          all.crackRefDiffers += t.crackRefDiffers; all.crackRejected += t.crackRejected;
          all.cameraJobs += t.cameraJobs; all.crackJobs += t.crackJobs;
          if (first || t.isectLatency >= 0) all.isectLatency = std::max(all.isectLatency, t.isectLatency);
          first = false;
        }
        if (scenes.size() > 1) scenes.push_back({"all", all});
        for (const auto& [name, t] : scenes) {
          const double lattice = double((int64_t(1) << w.pos) - 1);
          const bool timed = t.cycleAccurate && t.cameraJobs > 0;
          const double cyclesPerRay = timed ? ratio(double(t.cycles), double(t.inLattice)) : NAN;
          const double depth = syn.value("logic_depth", NAN);
          const double fmax = std::isfinite(depth) ? fmaxMhzOfDepth(depth) : NAN;
          const double nsPerRay = cyclesPerRay / fmax * 1e3;
          const double cells = syn.value("cells", NAN);
          const double tErrMean = ratio(t.tErrSum, double(t.compared));
          const bool hasCamera = t.cameraJobs > 0;
          nlohmann::json row = {
              {"width", w.name()}, {"pos_bits", w.pos}, {"dir_bits", w.dir}, {"unit", unit}, {"model", model},
              {"scene", name}, {"rays", t.rays}, {"rays_in_lattice", t.inLattice},
              {"disagreements", t.disagreements}, {"hit_miss_differs", t.hitMiss}, {"prim_differs", t.prim},
              {"misclassified_fraction", hasCamera ? num(ratio(double(t.disagreements), double(t.rays))) : nullptr},
              {"t_error_max_lattice", hasCamera ? num(t.tErrMax) : nullptr},
              {"t_error_mean_lattice", num(tErrMean)},
              {"t_error_max_relative", hasCamera ? num(t.tErrMax / lattice) : nullptr},
              {"t_error_mean_relative", num(tErrMean / lattice)},
              {"arbiter_hw_correct", t.arbHwCorrect}, {"arbiter_hw_tie", t.arbHwTie},
              {"arbiter_hw_within_bound", t.arbHwWithin}, {"arbiter_hw_beyond_bound", t.arbHwBeyond},
              {"arbiter_ref_wrong", t.arbRefWrong},
              {"crack_rays", t.crackJobs ? nlohmann::json(t.crackRays) : nullptr},
              {"cracks", t.crackJobs ? nlohmann::json(t.crackMisses) : nullptr},
              {"crack_ref_hit_miss_differs", t.crackJobs ? nlohmann::json(t.crackRefDiffers) : nullptr},
              {"crack_rays_rejected", t.crackJobs ? nlohmann::json(t.crackRejected) : nullptr},
              {"unit_steps", unit == "isect" ? nullptr : nlohmann::json(t.steps)},
              {"reference_steps", unit != "isect" && t.refComparable ? nlohmann::json(t.refNodes) : nullptr},
              {"extra_steps_fraction", unit != "isect" && t.refComparable
                                           ? num(ratio(double(t.steps), double(t.refNodes)) - 1.0) : nullptr},
              {"mismatches_vs_golden", t.mismatches},
              {"isect_latency_cycles", t.isectLatency >= 0 ? nlohmann::json(t.isectLatency) : nullptr},
              {"cycles", timed ? nlohmann::json(t.cycles) : nullptr},
              {"cycles_per_ray", num(cyclesPerRay)},
              {"tests_per_cycle", timed ? num(ratio(double(t.tests), double(t.cycles))) : nullptr},
              {"tests_per_ray", num(ratio(double(t.tests), double(t.inLattice)))},
              {"cells", num(cells)}, {"flip_flops", num(syn.value("flip_flops", NAN))},
              {"logic_depth", num(depth)}, {"fmax_mhz_est", num(fmax)}, {"ns_per_ray_at_fmax", num(nsPerRay)},
              {"cells_x_ns_per_ray", num(cells * nsPerRay)},
              {"host_model_seconds", t.modelSeconds},
              {"host_rays_per_second", num(ratio(double(t.inLattice), t.modelSeconds))},
              {"build_seconds", tree.value("build_seconds", nlohmann::json(nullptr))},
              {"synth_cpu_seconds", num(syn.value("cpu_seconds", NAN))}};
          rows.push_back(std::move(row));
        }
      }
    }
  }
  // The unit's own walk against itself at the widest width of the sweep (the
  // same structure on the same lattice cube, so what differs is the narrower
  // arithmetic's conservative stepping).
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
  m.rows = rows.size();

  std::string csv, exact;
  for (const Column& c : columns()) {
    csv += (csv.empty() ? "" : ",") + std::string(c.name);
    if (c.exact) exact += (exact.empty() ? "" : ",") + std::string(c.name);
  }
  csv += "\n";
  exact += "\n";
  for (const nlohmann::json& row : rows) {
    std::string line, exactLine;
    for (const Column& c : columns()) {
      const std::string cell = csvCell(row.at(c.name));
      line += (&c == &columns().front() ? "" : ",") + cell;
      if (c.exact) exactLine += (&c == &columns().front() ? "" : ",") + cell;
    }
    csv += line + "\n";
    exact += exactLine + "\n";
  }
  writeAtomically(out + "/sweep.csv", csv);
  writeAtomically(out + "/sweep-exact.csv", exact);

  // The terminal summary: per width, unit and scene, the most detailed model
  // (the last in the spec that has results: rtl after golden).
  if (table) {
    fmt::print(table, "{:<6} {:<6} {:<7} {:<14} {:>9} {:>10} {:>7} {:>7} {:>8} {:>7} {:>8} {:>7} {:>9} {:>7}\n",
               "width", "unit", "model", "scene", "misclass", "t err max", "cracks", "extra", "cyc/ray",
               "tst/cyc", "cells", "MHz", "host r/s", "build");
    const auto fmtNum = [](const nlohmann::json& v, const char* f) {
      return v.is_null() ? std::string("-") : fmt::format(fmt::runtime(f), v.get<double>());
    };
    for (const nlohmann::json& row : rows) {
      // Only the last model of each width/unit/scene.
      bool later = false;
      for (const nlohmann::json& other : rows) {
        if (&other == &row || other["width"] != row["width"] || other["unit"] != row["unit"] ||
            other["scene"] != row["scene"]) {
          continue;
        }
        const auto pos = [&](const nlohmann::json& r) {
          return std::find(spec.models.begin(), spec.models.end(), r["model"].get<std::string>()) - spec.models.begin();
        };
        later = later || pos(other) > pos(row);
      }
      if (later) continue;
      std::string scene = fs::path(row["scene"].get<std::string>()).stem().string();
      if (scene.size() > 14) scene = scene.substr(0, 14);
      const nlohmann::json mis = row["misclassified_fraction"];
      fmt::print(table, "{:<6} {:<6} {:<7} {:<14} {:>9} {:>10} {:>7} {:>7} {:>8} {:>7} {:>8} {:>7} {:>9} {:>7}\n",
                 row["width"].get<std::string>(), row["unit"].get<std::string>(), row["model"].get<std::string>(),
                 scene, mis.is_null() ? "-" : fmt::format("{:.4f}%", 100 * mis.get<double>()),
                 fmtNum(row["t_error_max_relative"], "{:.2e}"),
                 row["cracks"].is_null() ? "-" : fmt::format("{}/{}", row["cracks"].get<uint64_t>(), row["crack_rays"].get<uint64_t>()),
                 row["extra_steps_fraction"].is_null() ? "-" : fmt::format("{:+.1f}%", 100 * row["extra_steps_fraction"].get<double>()),
                 fmtNum(row["cycles_per_ray"], "{:.2f}"), fmtNum(row["tests_per_cycle"], "{:.3f}"),
                 fmtNum(row["cells"], "{:.0f}"), fmtNum(row["fmax_mhz_est"], "{:.0f}"),
                 fmtNum(row["host_rays_per_second"], "{:.0f}"), fmtNum(row["build_seconds"], "{:.0f}s"));
    }
  }

  if (plots && !rows.empty()) {
    const std::string log = out + "/plots.log";
    std::ofstream(log, std::ios::trunc).close();
    if (const int rc = runLogged({spec.source + "/scripts/sweep-plot", out}, log); rc != 0) {
      errors.push_back(fmt::format("plots: scripts/sweep-plot exited {}: {} (log {})", rc, lastLine(log), log));
    }
  }
  m.errors = errors.size();
  const nlohmann::json doc = {{"spec", spec.toJson()}, {"rows", rows}, {"trees", trees}, {"synth", synth},
                              {"missing_jobs", missing}, {"errors", errors},
                              {"gate_model", {{"gate_delay_ps", kGateDelayPs}, {"register_overhead_ps", kRegisterOverheadPs}}}};
  writeAtomically(out + "/sweep.json", doc.dump(2) + "\n");
  return m;
}

}  // namespace lancer::sweep
