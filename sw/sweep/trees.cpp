#include "sweep/trees.h"

#include <chrono>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>

#include "sweep/process.h"

namespace lancer::sweep {

namespace fs = std::filesystem;

namespace {

// A CMake cache entry ("NAME:TYPE=value"), or "" if absent.
std::string cacheValue(const std::string& tree, const std::string& name) {
  std::ifstream in(tree + "/CMakeCache.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(name + ":", 0) == 0) return line.substr(line.find('=') + 1);
  }
  return {};
}

bool ccacheAvailable() {
  int status = 0;
  runCaptured({"ccache", "--version"}, status);
  return status == 0;
}

}  // namespace

std::string lancerOf(const std::string& tree) { return tree + "/sw/lancer"; }

std::optional<double> recordedBuildSeconds(const std::string& tree) {
  const nlohmann::json m = readJson(tree + "/lancer-sweep-build.json");
  if (!m.is_object() || !m.contains("build_seconds")) return std::nullopt;
  return m["build_seconds"].get<double>();
}

nlohmann::json TreeResult::toJson() const {
  nlohmann::json j = {{"width", width.name()}, {"dir", dir}, {"ok", ok}, {"up_to_date", upToDate},
                      {"build_seconds", buildSeconds ? nlohmann::json(*buildSeconds) : nlohmann::json(nullptr)}};
  if (!error.empty()) j["error"] = error;
  return j;
}

TreeResult buildTree(const Spec& spec, const Width& w, const std::string& out) {
  TreeResult r;
  r.width = w;
  r.dir = fs::absolute(spec.treeOf(w)).lexically_normal().string();
  fs::create_directories(out + "/trees");
  r.log = fmt::format("{}/trees/{}.log", out, w.tag());
  std::ofstream(r.log, std::ios::trunc).close();
  const auto fail = [&](const std::string& what) {
    r.error = fmt::format("width {}: {} (log {})", w.name(), what, r.log);
    return r;
  };

  const bool configured = !fs::exists(r.dir + "/CMakeCache.txt");
  if (!configured) {
    const std::string p = cacheValue(r.dir, "LANCER_POS_BITS"), d = cacheValue(r.dir, "LANCER_DIR_BITS");
    if (p != std::to_string(w.pos) || d != std::to_string(w.dir)) {
      return fail(fmt::format("tree {} is configured for {}/{}, not {}", r.dir, p, d, w.name()));
    }
  } else {
    std::vector<std::string> configure{"cmake", "-S", spec.source, "-B", r.dir, "-G", "Ninja",
                                       "-DCMAKE_BUILD_TYPE=Release",
                                       fmt::format("-DLANCER_POS_BITS={}", w.pos),
                                       fmt::format("-DLANCER_DIR_BITS={}", w.dir)};
    if (ccacheAvailable()) {
      configure.push_back("-DCMAKE_CXX_COMPILER_LAUNCHER=ccache");
      configure.push_back("-DCMAKE_C_COMPILER_LAUNCHER=ccache");
    }
    configure.insert(configure.end(), spec.cmakeArgs.begin(), spec.cmakeArgs.end());
    if (const int rc = runLogged(configure, r.log); rc != 0) {
      return fail(fmt::format("configuring {} failed (exit {}): {}", r.dir, rc, errorLine(r.log)));
    }
  }

  // rt_pkg.sv for the syntheses. A tree without the hardware models
  // (--cmake-arg=-DLANCER_HW_MODELS=OFF: golden alone, minutes less a width)
  // has no waveform tool, and its syntheses no measured activity (scripts/sweep-synth).
  std::vector<std::string> build{"cmake", "--build", r.dir, "--target", "lancer", "rt_pkg"};
  if (cacheValue(r.dir, "LANCER_HW_MODELS") != "OFF") build.push_back("lancer_fst_activity");
  build.insert(build.end(), {"-j", std::to_string(spec.buildJobs)});
  const auto start = std::chrono::steady_clock::now();
  const int rc = runLogged(build, r.log);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (rc != 0) return fail(fmt::format("building lancer in {} failed (exit {}): {}", r.dir, rc, errorLine(r.log)));

  // Ninja says "no work to do" when the tree was up to date. The figure kept
  // in the tree is its first build, from a fresh configure (what a new width
  // costs); an incremental rebuild is only recorded if nothing better is known.
  std::ifstream in(r.log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  r.upToDate = text.find("ninja: no work to do") != std::string::npos;
  const std::string marker = r.dir + "/lancer-sweep-build.json";
  const std::optional<double> known = recordedBuildSeconds(r.dir);
  if (!r.upToDate && (configured || !known)) {
    writeAtomically(marker, nlohmann::json{{"build_seconds", seconds}, {"from_scratch", configured}}.dump() + "\n");
    r.buildSeconds = seconds;
  } else {
    r.buildSeconds = known;
  }
  if (!fs::exists(lancerOf(r.dir))) return fail(fmt::format("no {} after the build", lancerOf(r.dir)));
  r.ok = true;
  return r;
}

nlohmann::json synthTree(const Spec& spec, const Width& w, const std::string& top, const std::string& out) {
  const std::string tree = fs::absolute(spec.treeOf(w)).lexically_normal().string();
  const std::string cache = fmt::format("{}/synth/{}/sweep-synth.json", tree, top);
  // Reused while made from the same package and RTL sources (scripts/lancer_synth.py
  // decides, for scripts/clock-table too).
  int status = 0;
  const std::string cached =
      runCaptured({"python3", spec.source + "/scripts/lancer_synth.py", "cached", tree, top}, status);
  if (status == 0) {
    nlohmann::json j = nlohmann::json::parse(cached, nullptr, false);
    if (j.is_object()) {
      j["cached"] = true;
      return j;
    }
  }
  const std::string log = fmt::format("{}/trees/{}-synth-{}.log", out, w.tag(), top);
  std::ofstream(log, std::ios::trunc).close();
  const int rc = runLogged({spec.source + "/scripts/sweep-synth", tree, top, cache}, log);
  if (rc != 0) {
    return {{"error", fmt::format("width {}: synthesis of {} failed (exit {}): {} (log {})", w.name(), top, rc,
                                  errorLine(log), log)}};
  }
  nlohmann::json j = readJson(cache);
  if (!j.is_object()) return {{"error", fmt::format("width {}: synthesis of {} wrote no {}", w.name(), top, cache)}};
  j["cached"] = false;
  return j;
}

}  // namespace lancer::sweep
