// Host speed of every model of the intersection pipeline, side by side in one
// run on the same ray-triangle pairs (docs/performance.md, "Simulation speed of
// the intersection pipeline models").
//
//  1. Pairs (--pairs camera, the default): the scene's camera rays, quantized
//     by the driver's Quantizer, each with its candidate triangles from the
//     host BVH (driver/candidates.h) — exactly the stream `lancer run --accel
//     isect` feeds the pipeline. --pairs random: rtltest::randomPairs, the
//     distinct random pairs of the RTL tests (43 % hits, every pair a new ray).
//  2. Check pass: every model (--models, makeIsectDevice names; by default all
//     of isectDeviceNames(): golden, systemc (the cycle model on value ports,
//     clocked by the RTL's run loop), systemc-pins (the same model on pins in
//     the SystemC kernel), rtl, rtl-systemc) runs the pairs once; every result
//     must equal golden's bit for bit, or the program exits 1.
//  3. Timed passes: `--repetitions` rounds; each round runs every model once,
//     the order rotated each round, so load from other work hits all models
//     alike. A sample repeats the run until it lasts `--min-sample` seconds.
//     Wall clock and the thread's CPU clock are both taken; medians reported.
//  4. Icarus: the first `--icarus-pairs` pairs (at most 65536, the bench's
//     limit) are written as $readmemh vectors with golden results, compiled
//     and checked once by tests/rtl/isect/run_icarus.cmake (no stall, no idle),
//     then `vvp` is timed on them, and on one vector for its fixed cost.
//
// Output: a table on stdout and, with --json FILE, the same figures as JSON.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "driver/candidates.h"
#include "driver/devices.h"
#include "driver/quantize.h"
#include "golden/formats.h"
#include "golden/isect.h"
#include "golden/records.h"
#include "isect/isect_cases.h"
#include "ref/bvh.h"
#include "scene/camera.h"
#include "scene/scene.h"

extern char** environ;

namespace lancer {
namespace {

struct Config {
  std::string pairs = "camera";  // or "random"
  size_t randomPairs = 1000000;
  std::string scene;
  int width = 256, height = 256;
  size_t maxPairs = 0;  // 0: all
  int repetitions = 5;
  double minSample = 0.25;  // seconds
  std::vector<std::string> models;
  size_t icarusPairs = 20000;
  int icarusRepetitions = 3;
  std::string work;
  std::string json;
};

using bench::median;

// The pairs `lancer run --accel isect` streams for the scene's camera rays.
std::vector<IsectRequest> cameraPairs(const Scene& scene, const Config& config, size_t* raysInLattice) {
  CameraOptions camera;
  camera.width = config.width;
  camera.height = config.height;
  const std::vector<Ray> rays = frameScene(scene, camera).generateRays();
  const Quantizer quantizer(scene.bounds);
  const Bvh bvh(scene, AccelOptions{});
  const CandidateSource candidates = bvhCandidates(bvh, 2.0f * float(quantizer.unit()));
  std::vector<fx::QTriangle> triangles(scene.size());
  for (uint32_t i = 0; i < scene.size(); ++i) triangles[i] = quantizer.quantize(scene.triangles[i], i);
  std::vector<IsectRequest> pairs;
  std::vector<uint32_t> found;
  *raysInLattice = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    const auto q = quantizer.quantize(rays[i], uint32_t(i));
    if (!q) continue;
    ++*raysInLattice;
    found.clear();
    candidates(Ray{glm::vec3(quantizer.sceneOrigin(q->q)), glm::vec3(quantizer.sceneDirection(q->q))}, found);
    for (uint32_t prim : found) pairs.push_back({q->q, triangles[prim]});
    if (config.maxPairs && pairs.size() >= config.maxPairs) {
      pairs.resize(config.maxPairs);
      break;
    }
  }
  return pairs;
}

struct Timing {
  std::vector<double> wallRate, cpuRate;  // tests/s per sample
  int inner = 1;                          // runs per sample
};

// ---- Icarus -----------------------------------------------------------------

// A record as $readmemh digits: ceil(bits/4) hex digits, most significant first.
std::string hexDigits(std::span<const uint32_t> wire, int bits) {
  std::string s;
  for (int digit = (bits + 3) / 4 - 1; digit >= 0; --digit) {
    s += "0123456789abcdef"[(wire[size_t(digit / 8)] >> (4 * (digit % 8))) & 0xf];
  }
  return s;
}

// The vector files of make_isect_vectors (PREFIX.{ray,tri,res}.hex, PREFIX.count)
// for `pairs`, ray id = vector index as the bench reports it.
void writeVectors(const std::string& prefix, std::span<const IsectRequest> pairs) {
  std::ofstream ray(prefix + ".ray.hex"), tri(prefix + ".tri.hex"), res(prefix + ".res.hex");
  for (size_t i = 0; i < pairs.size(); ++i) {
    IsectRequest r = pairs[i];
    r.ray.id = uint32_t(i);
    ray << hexDigits(fx::packWire(r.ray), fx::kIsectRayBits) << '\n';
    tri << hexDigits(fx::packWire(r.tri), fx::kIsectTriBits) << '\n';
    res << hexDigits(fx::packWire(fx::intersect(r.ray, r.tri)), fx::kIsectResBits) << '\n';
  }
  std::ofstream(prefix + ".count") << pairs.size() << '\n';
  if (!ray || !tri || !res) throw std::runtime_error("cannot write " + prefix + ".*.hex");
}

struct ChildRun {
  int status = -1;
  double wall = 0, cpu = 0;  // cpu: the child's user + system time
  std::string output;
};

// Runs argv with stdout and stderr to `log`; wall and CPU time of the child.
ChildRun runChild(const std::vector<std::string>& argv, const std::string& log) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  ChildRun run;
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int err = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) throw std::runtime_error(fmt::format("cannot start {}: {}", argv[0], std::strerror(err)));
  rusage usage{};
  int status = 0;
  if (wait4(pid, &status, 0, &usage) < 0) throw std::runtime_error("wait4 failed");
  run.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.cpu = double(usage.ru_utime.tv_sec) + 1e-6 * double(usage.ru_utime.tv_usec) +
            double(usage.ru_stime.tv_sec) + 1e-6 * double(usage.ru_stime.tv_usec);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  run.output = text.str();
  return run;
}

struct IcarusResult {
  size_t pairs = 0;
  std::vector<double> wall, cpu;  // seconds per full run
  double fixedWall = 0, fixedCpu = 0;  // one vector: start-up, $readmemh, reset
};

std::optional<IcarusResult> timeIcarus(std::span<const IsectRequest> all, const Config& config) {
#if defined(LANCER_BENCH_VVP)
  const size_t n = std::min<size_t>({all.size(), config.icarusPairs, 65536});
  if (n == 0) return std::nullopt;
  const std::string work = config.work + "/icarus";
  std::filesystem::create_directories(work);
  writeVectors(work + "/vectors", all.subspan(0, n));
  // run_icarus.cmake makes the Icarus-11 copies, compiles, runs once and checks
  // every result; its vector tool is `true`, since the vectors are already there.
  const ChildRun check = runChild({LANCER_BENCH_CMAKE, "-DVECTOR_TOOL=" LANCER_BENCH_TRUE,
                                   "-DIVERILOG=" LANCER_BENCH_IVERILOG, "-DVVP=" LANCER_BENCH_VVP,
                                   "-DPKG=" LANCER_BENCH_PKG, "-DDUT=" LANCER_BENCH_DUT, "-DTB=" LANCER_BENCH_TB,
                                   "-DWORK=" + work, "-DSTALL=0", "-DIDLE=0", "-P", LANCER_BENCH_RUN_ICARUS},
                                  work + "/check.log");
  if (check.status != 0) {
    throw std::runtime_error(fmt::format("Icarus check failed (see {}/check.log):\n{}", work, check.output));
  }
  IcarusResult result;
  result.pairs = n;
  auto vvp = [&](size_t count) {
    const ChildRun r = runChild({LANCER_BENCH_VVP, "-n", work + "/tb_rt_isect.vvp", "+vectors=" + work + "/vectors",
                                 fmt::format("+n={}", count), "+seed=1", "+stall=0", "+idle=0"},
                                work + "/vvp.log");
    if (r.status != 0 || r.output.find(fmt::format("tb_rt_isect: {} passed, 0 failed", count)) == std::string::npos) {
      throw std::runtime_error(fmt::format("vvp failed on {} vectors:\n{}", count, r.output));
    }
    return r;
  };
  std::vector<double> fixedWall, fixedCpu;
  for (int i = 0; i < config.icarusRepetitions; ++i) {
    const ChildRun one = vvp(1);
    fixedWall.push_back(one.wall);
    fixedCpu.push_back(one.cpu);
    const ChildRun full = vvp(n);
    result.wall.push_back(full.wall);
    result.cpu.push_back(full.cpu);
  }
  result.fixedWall = median(fixedWall);
  result.fixedCpu = median(fixedCpu);
  return result;
#else
  (void)all;
  (void)config;
  return std::nullopt;
#endif
}

// ---- Machine facts -----------------------------------------------------------

std::string firstLineWith(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(key, 0) == 0) {
      const auto colon = line.find(':');
      return colon == std::string::npos ? line : line.substr(colon + 2);
    }
  }
  return "";
}

double loadAverage() {
  double load[1] = {0};
  return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

int run(const Config& config) {
  const bool camera = config.pairs == "camera";
  const Scene scene = camera ? loadScene(config.scene) : Scene{};
  size_t raysInLattice = 0;
  const std::vector<IsectRequest> pairs =
      camera ? cameraPairs(scene, config, &raysInLattice) : rtltest::randomPairs(config.randomPairs, 2024);
  if (pairs.empty()) throw std::runtime_error("no pairs: the camera sees nothing of the scene");
  const double loadBefore = loadAverage();
  if (camera) {
    fmt::print("isect_models_bench: {} ({} triangles), {}x{} camera rays, {} in the lattice, {} pairs, "
               "formats pos {} / dir {} bits\n",
               scene.name, scene.size(), config.width, config.height, raysInLattice, pairs.size(), fx::kPosBits,
               fx::kDirBits);
  } else {
    fmt::print("isect_models_bench: {} random pairs (rtltest::randomPairs, seed 2024), formats pos {} / dir {} bits\n",
               pairs.size(), fx::kPosBits, fx::kDirBits);
  }

  // Check pass: bit for bit against golden; also calibrates the sample length.
  std::vector<std::unique_ptr<IsectDevice>> devices;
  for (const auto& name : config.models) devices.push_back(makeIsectDevice(name));
  std::vector<fx::IsectResult> golden, results;
  golden.reserve(pairs.size());
  results.reserve(pairs.size());
  makeIsectDevice("golden")->run(pairs, golden);
  size_t hits = 0;
  for (const auto& r : golden) hits += r.hit;
  std::vector<Timing> timing(devices.size());
  std::vector<uint64_t> cycles(devices.size());
  for (size_t m = 0; m < devices.size(); ++m) {
    results.clear();
    const auto start = std::chrono::steady_clock::now();
    cycles[m] = devices[m]->run(pairs, results).cycles;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (results != golden) {
      fmt::print(stderr, "isect_models_bench: {} differs from golden\n", devices[m]->name());
      return 1;
    }
    timing[m].inner = std::max(1, int(config.minSample / std::max(seconds, 1e-6) + 0.5));
  }
  fmt::print("  check: every model bit-identical to golden ({} hits)\n", hits);

  // Timed rounds, the order rotated each round.
  bench::rotatedRounds(config.repetitions, devices.size(), [&](size_t m) {
    Timing& t = timing[m];
    const bench::Sample s = bench::timeSample([&] {
      for (int i = 0; i < t.inner; ++i) {
        results.clear();
        devices[m]->run(pairs, results);
      }
    });
    const double tests = double(pairs.size()) * t.inner;
    t.wallRate.push_back(tests / s.wall);
    t.cpuRate.push_back(tests / s.cpu);
  });

  const std::optional<IcarusResult> icarus = config.icarusPairs ? timeIcarus(pairs, config) : std::nullopt;
  const double loadAfter = loadAverage();

  // Report.
  nlohmann::json out;
  out["pair_source"] = config.pairs;
  if (camera) {
    out["scene"] = scene.name;
    out["triangles"] = scene.size();
    out["width"] = config.width;
    out["height"] = config.height;
    out["rays_in_lattice"] = raysInLattice;
  }
  out["pairs"] = pairs.size();
  out["hits"] = hits;
  out["pos_bits"] = fx::kPosBits;
  out["dir_bits"] = fx::kDirBits;
  out["repetitions"] = config.repetitions;
  out["machine"] = {{"cpu", firstLineWith("/proc/cpuinfo", "model name")},
                    {"nproc", std::thread::hardware_concurrency()},
                    {"load_average_before", loadBefore},
                    {"load_average_after", loadAfter}};
  const size_t goldenIndex =
      size_t(std::find(config.models.begin(), config.models.end(), "golden") - config.models.begin());
  const bool haveGolden = goldenIndex < config.models.size();
  const double goldenWall = haveGolden ? median(timing[goldenIndex].wallRate) : 0.0;
  const double goldenCpu = haveGolden ? median(timing[goldenIndex].cpuRate) : 0.0;

  fmt::print("  {:<12} {:>12} {:>9} {:>9} {:>12} {:>11} {:>11} {:>6}\n", "model", "M tests/s", "min", "max",
             "cpu M t/s", "/golden", "cpu /golden", "runs");
  auto row = [&](const std::string& name, const std::vector<double>& wallRate, const std::vector<double>& cpuRate,
                 int inner) {
    const double wall = median(wallRate), cpu = median(cpuRate);
    const auto [lo, hi] = std::minmax_element(wallRate.begin(), wallRate.end());
    fmt::print("  {:<12} {:>12.4f} {:>9.4f} {:>9.4f} {:>12.4f} {:>11.5f} {:>11.5f} {:>6}\n", name, wall / 1e6,
               *lo / 1e6, *hi / 1e6, cpu / 1e6, goldenWall > 0 ? wall / goldenWall : 0.0,
               goldenCpu > 0 ? cpu / goldenCpu : 0.0, inner);
    nlohmann::json j = {{"tests_per_s", wall},
                        {"tests_per_s_min", *lo},
                        {"tests_per_s_max", *hi},
                        {"cpu_tests_per_s", cpu},
                        {"samples_wall", wallRate},
                        {"samples_cpu", cpuRate},
                        {"runs_per_sample", inner}};
    if (goldenWall > 0) {
      j["ratio_to_golden"] = wall / goldenWall;
      j["cpu_ratio_to_golden"] = cpu / goldenCpu;
    }
    return j;
  };
  for (size_t m = 0; m < devices.size(); ++m) {
    out["models"][config.models[m]] = row(config.models[m], timing[m].wallRate, timing[m].cpuRate, timing[m].inner);
    out["models"][config.models[m]]["cycles"] = cycles[m];
  }
  if (icarus) {
    // Net of the fixed cost (start-up, $readmemh of the vector files, reset):
    // (n - 1) more vectors for (full - one) more time.
    std::vector<double> wallRate, cpuRate;
    for (size_t i = 0; i < icarus->wall.size(); ++i) {
      wallRate.push_back(double(icarus->pairs - 1) / std::max(1e-9, icarus->wall[i] - icarus->fixedWall));
      cpuRate.push_back(double(icarus->pairs - 1) / std::max(1e-9, icarus->cpu[i] - icarus->fixedCpu));
    }
    out["models"]["icarus"] = row("icarus", wallRate, cpuRate, 1);
    out["models"]["icarus"]["pairs"] = icarus->pairs;
    out["models"]["icarus"]["seconds_wall"] = icarus->wall;
    out["models"]["icarus"]["seconds_cpu"] = icarus->cpu;
    out["models"]["icarus"]["fixed_seconds_wall"] = icarus->fixedWall;
    out["models"]["icarus"]["fixed_seconds_cpu"] = icarus->fixedCpu;
    fmt::print("  icarus: first {} pairs, median {:.2f} s wall / {:.2f} s cpu per run, of which {:.2f} / {:.2f} s "
               "fixed (one vector); rates are net of it\n",
               icarus->pairs, median(icarus->wall), median(icarus->cpu), icarus->fixedWall, icarus->fixedCpu);
  }
  fmt::print("  wall-clock medians of {} samples (min, max), thread CPU clock (vvp: child CPU); load average "
             "{:.2f} before, {:.2f} after\n",
             config.repetitions, loadBefore, loadAfter);
  if (!config.json.empty()) {
    std::ofstream(config.json) << out.dump(2) << '\n';
    fmt::print("  report: {}\n", config.json);
  }
  return 0;
}

}  // namespace
}  // namespace lancer

int main(int argc, char** argv) {
  lancer::Config config;
  config.scene = std::filesystem::exists(LANCER_BENCH_BUNNY) ? LANCER_BENCH_BUNNY : "builtin:cornell";
  config.models = lancer::isectDeviceNames();
  config.work = (std::filesystem::temp_directory_path() / "isect_models_bench").string();
  CLI::App app{"Host speed of every model of the intersection pipeline on the same pairs"};
  app.add_option("--pairs", config.pairs, "camera: the scene's camera rays x BVH candidates; random: random pairs")
      ->check(CLI::IsMember({"camera", "random"}))
      ->capture_default_str();
  app.add_option("--random-pairs", config.randomPairs, "How many random pairs (--pairs random)")
      ->capture_default_str();
  app.add_option("--scene", config.scene, "Scene (default: the bunny if fetched, else builtin:cornell)")
      ->capture_default_str();
  app.add_option("--width", config.width, "Camera rays across")->capture_default_str();
  app.add_option("--height", config.height, "Camera rays down")->capture_default_str();
  app.add_option("--max-pairs", config.maxPairs, "Keep at most this many pairs (0: all)")->capture_default_str();
  app.add_option("--repetitions", config.repetitions, "Timed rounds (median reported)")->capture_default_str();
  app.add_option("--min-sample", config.minSample, "Seconds a sample lasts at least (runs repeated)")
      ->capture_default_str();
  app.add_option("--models", config.models, "Models to time (makeIsectDevice names)")->delimiter(',');
  app.add_option("--icarus-pairs", config.icarusPairs, "Pairs timed under Icarus, at most 65536 (0: skip)")
      ->capture_default_str();
  app.add_option("--icarus-repetitions", config.icarusRepetitions, "Icarus runs (median reported)")
      ->capture_default_str();
  app.add_option("--work", config.work, "Directory for the Icarus vectors and build")->capture_default_str();
  app.add_option("--json", config.json, "JSON report file");
  CLI11_PARSE(app, argc, argv);
  try {
    return lancer::run(config);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "isect_models_bench: %s\n", e.what());
    return 1;
  }
}
