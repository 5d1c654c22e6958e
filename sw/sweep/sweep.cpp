#include "sweep/sweep.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <thread>

#include <fmt/format.h>

#include "common/error.h"
#include "common/progress.h"
#include "scene/camera.h"
#include "scene/rays_file.h"
#include "scene/scene.h"
#include "sweep/job.h"
#include "sweep/merge.h"
#include "sweep/process.h"
#include "sweep/trees.h"

namespace lancer::sweep {

namespace fs = std::filesystem;

namespace {

void failJob(const std::string& out, const Spec& spec, const Job& job, const std::string& why) {
  fs::create_directories(out + "/jobs");
  writeAtomically(jobErrorPath(out, job),
                  nlohmann::json{{"job", job.toJson()}, {"error", fmt::format("{}: {}", job.describe(spec), why)}}.dump(2) +
                      "\n");
}

// What the sweep found of one scene before running any job.
struct SceneCheck {
  std::string error;         // why it does not load, or ""
  bool hasQuadrics = false;  // read natively, it has a sphere or a cone (asked only with the quadric unit)
};

// Loads every scene and writes its camera rays in chunks; with the quadric
// unit, reads each natively first (again tessellated only if it has quadrics),
// so that its jobs on a scene without spheres or cones fail before they run.
std::vector<SceneCheck> writeCameraRays(const std::string& out, const Spec& spec) {
  fs::create_directories(out + "/rays");
  const bool quadricUnit = std::ranges::find(spec.units, "quadric") != spec.units.end();
  std::vector<SceneCheck> checks(spec.scenes.size());
  for (int s = 0; s < int(spec.scenes.size()); ++s) {
    try {
      const std::string& name = spec.scenes[size_t(s)];
      Scene scene = loadScene(name, quadricUnit ? QuadricForm::Native : QuadricForm::Tessellate);
      checks[size_t(s)].hasQuadrics = !scene.quadrics.empty();
      // The camera rays are the tessellated scene's; without quadrics both forms read the same.
      if (checks[size_t(s)].hasQuadrics) scene = loadScene(name);
      CameraOptions camera;
      camera.width = camera.height = spec.image;
      const std::vector<Ray> rays = frameScene(scene, camera).generateRays();
      for (int c = 0; c < spec.chunks; ++c) {
        const size_t from = rays.size() * size_t(c) / size_t(spec.chunks);
        const size_t to = rays.size() * size_t(c + 1) / size_t(spec.chunks);
        const std::vector<Ray> chunk(rays.begin() + long(from), rays.begin() + long(to));
        writeRaysFile(cameraRaysPath(out, spec, s, c), chunk,
                      fmt::format("{}: camera {}x{}, rays {}..{}", name, spec.image, spec.image,
                                  from, to - 1));
      }
    } catch (const InputError& e) {
      checks[size_t(s)].error = fmt::format("scene {} does not load: {}", spec.scenes[size_t(s)], e.what());
    }
  }
  return checks;
}

int runLocal(const std::string& out, const Spec& spec, const std::vector<Job>& jobs, int parallel,
             std::vector<std::string>& errors) {
  Progress progress(fmt::format("sweep ({} jobs)", jobs.size()), jobs.size());
  std::atomic<size_t> next{0};
  std::mutex mutex;
  std::vector<std::thread> workers;
  for (int w = 0; w < parallel; ++w) {
    workers.emplace_back([&] {
      for (size_t i; (i = next++) < jobs.size();) {
        std::string error;
        try {
          error = executeJob(out, spec, jobs[i]);
        } catch (const std::exception& e) {
          error = fmt::format("{}: {}", jobs[i].describe(spec), e.what());
        }
        const std::lock_guard lock(mutex);
        if (!error.empty()) errors.push_back(error);
        progress.advance();
      }
    });
  }
  for (std::thread& t : workers) t.join();
  progress.finish();
  return errors.empty() ? 0 : 1;
}

std::string selfPath() { return fs::read_symlink("/proc/self/exe").string(); }

// Submits the jobs as one Slurm array (one task a job) and a merge job that
// runs after it whatever the tasks' outcome. Returns the merge job's id.
std::string submitSlurm(const std::string& out, const std::vector<Job>& jobs, const RunOptions& options) {
  const std::string dir = out + "/slurm";
  fs::create_directories(dir);
  const std::string list = dir + "/jobs.txt";
  std::string keys;
  for (const Job& j : jobs) keys += j.key + "\n";
  writeAtomically(list, keys);
  const std::string self = selfPath();
  int status = 0;
  std::string dependency;
  if (!jobs.empty()) {
    std::vector<std::string> array{"sbatch", "--parsable", "--job-name=lancer-sweep",
                                   fmt::format("--array=0-{}", jobs.size() - 1), "--cpus-per-task=1",
                                   "--output=" + dir + "/task-%a.out"};
    array.insert(array.end(), options.sbatchArgs.begin(), options.sbatchArgs.end());
    array.push_back("--wrap=" + shellJoin({self, "sweep-job", "--out", out, "--list", list, "--task"}) +
                    " \"$SLURM_ARRAY_TASK_ID\"");
    std::string id = runCaptured(array, status);
    if (status != 0) throw InputError(fmt::format("sbatch of the {} sweep jobs failed (exit {})", jobs.size(), status));
    id = id.substr(0, id.find_first_of(";\n"));
    fmt::print("sweep: submitted {} jobs as Slurm array {}\n", jobs.size(), id);
    dependency = "--dependency=afterany:" + id;
  }
  std::vector<std::string> merge{"sbatch", "--parsable", "--job-name=lancer-sweep-merge", "--output=" + dir + "/merge.out"};
  if (!dependency.empty()) merge.push_back(dependency);
  if (options.wait) merge.push_back("--wait");
  merge.insert(merge.end(), options.sbatchArgs.begin(), options.sbatchArgs.end());
  merge.push_back("--wrap=" + shellJoin({self, "sweep-merge", "--out", out}));
  if (!options.wait) {
    std::string id = runCaptured(merge, status);
    if (status != 0) throw InputError(fmt::format("sbatch of the merge job failed (exit {})", status));
    id = id.substr(0, id.find_first_of(";\n"));
    fmt::print("sweep: merge job {} runs after them; results in {}\n", id, out);
    return id;
  }
  fmt::print("sweep: waiting for the merge job\n");
  std::fflush(stdout);
  runCaptured(merge, status);
  return {};
}

}  // namespace

int runSweep(const Spec& spec, const RunOptions& options) {
  spec.validate();
  if (options.executor != "local" && options.executor != "slurm") {
    throw InputError(fmt::format("--executor {}: must be local or slurm", options.executor));
  }
  const std::string out = fs::absolute(options.out).lexically_normal().string();
  fs::create_directories(out);
  const std::vector<Job> plan = makePlan(spec);
  nlohmann::json jobs = nlohmann::json::array();
  for (const Job& j : plan) jobs.push_back(j.toJson());
  writeAtomically(out + "/plan.json", nlohmann::json{{"spec", spec.toJson()}, {"jobs", jobs}}.dump(2) + "\n");

  std::vector<std::string> errors;
  const std::vector<SceneCheck> scenes = writeCameraRays(out, spec);
  std::vector<Job> todo;
  std::set<Width> needed;
  size_t done = 0;
  for (const Job& j : plan) {
    if (jobDone(out, spec, j)) {
      ++done;
    } else if (!scenes[size_t(j.scene)].error.empty()) {
      failJob(out, spec, j, scenes[size_t(j.scene)].error);
    } else if (j.unit == "quadric" && !scenes[size_t(j.scene)].hasQuadrics) {
      failJob(out, spec, j, "the scene has no sphere or cone: the quadric unit would test nothing (sweep it with isect)");
    } else {
      todo.push_back(j);
      needed.insert(j.width);
    }
  }
  for (const SceneCheck& scene : scenes) {
    if (!scene.error.empty()) errors.push_back(scene.error);
  }
  fmt::print("sweep: {} jobs planned, {} with results, {} to run, in {}\n", plan.size(), done, todo.size(), out);
  // A synthesis reads its tree's generated package: a width whose last
  // synthesis failed or never ran needs its tree too.
  if (spec.synth) {
    nlohmann::json synth = readJson(out + "/synth.json");
    if (!synth.is_object()) synth = nlohmann::json::object();
    for (const Width& w : spec.widths) {
      for (const std::string& unit : spec.synthesizedUnits()) {
        const nlohmann::json s = synth.value(w.name(), nlohmann::json::object()).value(synthTopOf(unit), nlohmann::json());
        if (!s.is_object() || s.contains("error")) needed.insert(w);
      }
    }
  }

  // The trees of the widths that have jobs to run or a synthesis to make (the
  // others keep their record).
  nlohmann::json trees = readJson(out + "/trees.json");
  if (!trees.is_object()) trees = nlohmann::json::object();
  std::set<Width> broken;
  for (const Width& w : spec.widths) {
    if (!needed.count(w)) {
      // Not rebuilt: its record, with the build time its tree holds now.
      if (trees.contains(w.name())) {
        const std::optional<double> s = recordedBuildSeconds(trees[w.name()].value("dir", spec.treeOf(w)));
        trees[w.name()]["build_seconds"] = s ? nlohmann::json(*s) : nlohmann::json(nullptr);
      }
      continue;
    }
    fmt::print("sweep: width {}: building lancer in {}\n", w.name(), spec.treeOf(w));
    std::fflush(stdout);
    const TreeResult t = buildTree(spec, w, out);
    trees[w.name()] = t.toJson();
    if (!t.ok) {
      errors.push_back(t.error);
      broken.insert(w);
    } else {
      fmt::print("sweep: width {}: {}\n", w.name(),
                 t.upToDate ? "up to date" : "brought up to date");
    }
    writeAtomically(out + "/trees.json", trees.dump(2) + "\n");
  }
  writeAtomically(out + "/trees.json", trees.dump(2) + "\n");
  if (spec.synth) {
    nlohmann::json synth = readJson(out + "/synth.json");
    if (!synth.is_object()) synth = nlohmann::json::object();
    for (const Width& w : spec.widths) {
      if (broken.count(w)) continue;
      for (const std::string& unit : spec.synthesizedUnits()) {
        const std::string top = synthTopOf(unit);
        fmt::print("sweep: width {}: synthesis of {}\n", w.name(), top);
        std::fflush(stdout);
        nlohmann::json s = synthTree(spec, w, top, out);
        if (s.contains("error")) errors.push_back(s["error"].get<std::string>());
        synth[w.name()][top] = std::move(s);
        writeAtomically(out + "/synth.json", synth.dump(2) + "\n");
      }
    }
  }
  std::vector<Job> runnable;
  for (const Job& j : todo) {
    if (broken.count(j.width)) {
      failJob(out, spec, j, trees[j.width.name()].value("error", "the width's build failed"));
    } else {
      runnable.push_back(j);
    }
  }

  if (options.executor == "slurm") {
    submitSlurm(out, runnable, options);
    if (!options.wait) return errors.empty() ? 0 : 1;
    const MergeResult m = mergeSweep(out, stdout, false);
    if (m.missing || m.errors || !errors.empty()) {
      const nlohmann::json doc = readJson(out + "/sweep.json");
      for (const auto& e : doc.value("errors", nlohmann::json::array())) fmt::print(stderr, "sweep: error: {}\n", e.get<std::string>());
      for (const std::string& e : errors) fmt::print(stderr, "sweep: error: {}\n", e);
      return 1;
    }
    return 0;
  }
  const int parallel = options.jobs > 0 ? options.jobs : int(std::max(1u, std::thread::hardware_concurrency()));
  runLocal(out, spec, runnable, parallel, errors);
  const MergeResult m = mergeSweep(out, stdout, options.plots);
  const nlohmann::json doc = readJson(out + "/sweep.json");
  std::set<std::string> shown;
  for (const std::string& e : errors) shown.insert(e);
  for (const auto& e : doc.value("errors", nlohmann::json::array())) shown.insert(e.get<std::string>());
  for (const std::string& e : shown) fmt::print(stderr, "sweep: error: {}\n", e);
  fmt::print("sweep: {} rows in {}/sweep.csv, {} jobs without a result\n", m.rows, out, m.missing);
  return shown.empty() && m.missing == 0 ? 0 : 1;
}

int runListedJob(const std::string& out, const std::string& list, int task) {
  const nlohmann::json plan = readJson(out + "/plan.json");
  if (!plan.is_object()) throw InputError(fmt::format("{}/plan.json: no sweep plan", out));
  const Spec spec = Spec::fromJson(plan.at("spec"), out + "/plan.json");
  std::ifstream in(list);
  if (!in) throw InputError(fmt::format("{}: cannot read the job list", list));
  std::string key;
  for (int i = 0; std::getline(in, key); ++i) {
    if (i != task) continue;
    for (const nlohmann::json& j : plan.at("jobs")) {
      if (j.at("key") != key) continue;
      const std::string error = executeJob(out, spec, Job::fromJson(j));
      if (!error.empty()) {
        fmt::print(stderr, "lancer: error: {}\n", error);
        return 1;
      }
      return 0;
    }
    throw InputError(fmt::format("{}: job {} is not in {}/plan.json", list, key, out));
  }
  throw InputError(fmt::format("{}: no task {} (the list is shorter)", list, task));
}

}  // namespace lancer::sweep
