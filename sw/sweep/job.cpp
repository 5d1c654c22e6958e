#include "sweep/job.h"

#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "golden/units.h"
#include "sweep/process.h"
#include "sweep/trees.h"

namespace lancer::sweep {

namespace fs = std::filesystem;

nlohmann::json jobInputs(const Spec& spec, const Job& job) {
  nlohmann::json j = {{"scene", spec.scenes[size_t(job.scene)]}, {"seed", spec.seed},
                      {"mem_latency", spec.memLatency}, {"grid_res", spec.gridRes},
                      {"clock_mhz", spec.clockMhz ? nlohmann::json(*spec.clockMhz) : nlohmann::json()}};
  if (job.set == "camera") {
    j["image"] = spec.image;
    j["chunks"] = spec.chunks;
  } else {
    j["crack_rays"] = spec.crackRays;
  }
  return j;
}

std::string jobResultPath(const std::string& out, const Job& job) { return fmt::format("{}/jobs/{}.json", out, job.key); }
std::string jobErrorPath(const std::string& out, const Job& job) {
  return fmt::format("{}/jobs/{}.error.json", out, job.key);
}
std::string cameraRaysPath(const std::string& out, const Spec& spec, int scene, int chunk) {
  return fmt::format("{}/rays/{}.c{}of{}.rays", out, sceneTag(spec, scene), chunk, spec.chunks);
}

bool jobDone(const std::string& out, const Spec& spec, const Job& job) {
  const nlohmann::json j = readJson(jobResultPath(out, job));
  return j.is_object() && j.value("inputs", nlohmann::json()) == jobInputs(spec, job) && j.contains("run");
}

std::string executeJob(const std::string& out, const Spec& spec, const Job& job) {
  fs::create_directories(out + "/jobs");
  const std::string tree = fs::absolute(spec.treeOf(job.width)).lexically_normal().string();
  const std::string lancer = lancerOf(tree);
  const std::string scene = spec.scenes[size_t(job.scene)];
  const std::string log = fmt::format("{}/jobs/{}.log", out, job.key);
  const std::string work = fmt::format("{}/jobs/{}", out, job.key);
  std::ofstream(log, std::ios::trunc).close();
  fs::create_directories(work);
  fs::remove(jobErrorPath(out, job));

  const auto fail = [&](const std::string& what) {
    const std::string error = fmt::format("{}: {} (log {})", job.describe(spec), what, log);
    writeAtomically(jobErrorPath(out, job), nlohmann::json{{"job", job.toJson()}, {"error", error}}.dump(2) + "\n");
    return error;
  };
  if (!fs::exists(lancer)) return fail(fmt::format("no {} (the width's build failed or never ran)", lancer));
  const auto step = [&](const std::vector<std::string>& argv, const std::string& what) {
    const int rc = runLogged(argv, log);
    return rc == 0 ? std::string() : fail(fmt::format("{} exited {}: {}", what, rc, errorLine(log)));
  };

  nlohmann::json result = {{"job", job.toJson()}, {"inputs", jobInputs(spec, job)}, {"tree", tree}};
  std::string rays;
  if (job.set == "cracks") {
    rays = work + "/cracks.rays";
    const std::string report = work + "/cracks.json";
    std::vector<std::string> crack{lancer, "crack-rays", "--scene", scene, "--count", std::to_string(spec.crackRays),
                                   "--seed", std::to_string(spec.seed), "--out", rays, "--report", report};
    const std::vector<std::string> form = quadricFormArgs(job.unit);
    crack.insert(crack.end(), form.begin(), form.end());
    if (std::string e = step(crack, "lancer crack-rays");
        !e.empty()) {
      return e;
    }
    result["cracks"] = readJson(report);
  } else {
    rays = cameraRaysPath(out, spec, job.scene, job.chunk);
  }

  const std::string runReport = work + "/run.json";
  std::vector<std::string> run{lancer, "run", "--scene", scene, "--rays", rays, "--model", job.model,
                               "--pos-bits", std::to_string(job.width.pos), "--dir-bits",
                               std::to_string(job.width.dir), "--report", runReport, "--repro",
                               work + "/mismatch.rays"};
  const std::vector<std::string> unitArgs = runUnitArgs(job.unit);
  run.insert(run.end(), unitArgs.begin(), unitArgs.end());
  if (spec.clockMhz) run.insert(run.end(), {"--clock-mhz", fmt::format("{}", *spec.clockMhz)});
  std::vector<std::string> structure;
  if (job.unit == "grid" && spec.gridRes) structure = {"--grid-res", std::to_string(spec.gridRes)};
  run.insert(run.end(), structure.begin(), structure.end());
  if (isTraversalUnit(job.unit)) run.insert(run.end(), {"--mem-latency", std::to_string(spec.memLatency)});
  // A run whose only failure is answers beyond the hardware's bound (exit 4, no
  // mismatch) keeps its result: the merge counts them as the sweep's failures.
  const int rc = runLogged(run, log);
  result["run"] = readJson(runReport);
  const bool onlyBeyond = rc == 4 && result["run"].is_object() && result["run"].value("mismatches", 1) == 0;
  if (rc != 0 && !onlyBeyond) return fail(fmt::format("lancer run exited {}: {}", rc, errorLine(log)));
  if (!result["run"].is_object()) return fail(fmt::format("lancer run wrote no report {}", runReport));

  // The float structure's walk on the same rays, with the hardware's structure
  // parameters: what the conservative fixed-point walk visits beyond it.
  if (isTraversalUnit(job.unit)) {
    const nlohmann::json& r = result["run"];
    std::vector<std::string> trace{lancer, "trace", "--scene", scene, "--rays", rays, "--report",
                                   work + "/trace.json", "--hits", "/dev/null"};
    const std::vector<std::string> unitArgs = runUnitArgs(job.unit);
    trace.insert(trace.end(), unitArgs.begin(), unitArgs.end());
    // Each build option as the unit reported it (the float grid is cubic: its
    // three axes must agree; the BVH is the same SAH builder over float boxes).
    bool comparable = true;
    fx::forEachTraversalUnit([&](auto unit) {
      if (job.unit != decltype(unit)::kNames.unit) return;
      for (const fx::BuildOption& o : decltype(unit)::buildOptions()) {
        if (!o.shapesReference) continue;
        const int64_t value = r.value(o.reportKeys.front(), 0);
        for (const char* key : o.reportKeys) comparable = comparable && r.value(key, 0) == value;
        comparable = comparable && value > 0;
        trace.insert(trace.end(), {o.flag, std::to_string(value)});
      }
    });
    if (comparable) {
      if (std::string e = step(trace, "lancer trace"); !e.empty()) return e;
      result["reference_trace"] = readJson(work + "/trace.json");
    }
  }
  writeAtomically(jobResultPath(out, job), result.dump(2) + "\n");
  return {};
}

}  // namespace lancer::sweep
