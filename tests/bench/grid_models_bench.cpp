// Host speed of every model of the grid traversal unit, side by side in one run
// on the same rays (docs/grid-unit.md, "Measured performance").
//
//  1. Rays: the scene's camera rays (frameScene, --width x --height), quantized
//     by the driver's Quantizer (rays that miss the lattice cube are dropped);
//     the grid the driver builds (fx::chooseGridResolution). --order shuffled
//     feeds the same rays in a random order (seed 1) instead of scanline order.
//  2. Check pass: every model (makeTraversalDevice) runs the rays once; every trace
//     must equal golden's bit for bit, or the program exits 1. Its simulated
//     figures (cycles, steps per cycle, isect busy, ...) are printed.
//  3. Timed passes: `--repetitions` rounds; each round runs every model once,
//     the order rotated each round, so load from other work hits all models
//     alike. Wall clock and the thread's CPU clock are both taken; medians
//     reported, as rays/s (host) and simulated cycles/s.
//
// Output: tables on stdout and, with --json FILE, the same figures as JSON.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench_support.h"
#include "driver/devices.h"
#include "driver/quantize.h"
#include "golden/grid.h"
#include "scene/camera.h"
#include "scene/scene.h"

using namespace lancer;
using bench::median;
using bench::Sample;

int main(int argc, char** argv) {
  CLI::App app{"Host speed of every model of the grid unit, side by side"};
  std::string scenePath = LANCER_BENCH_BUNNY;
  int width = 256, height = 256, repetitions = 5, raysInFlight = 0, memLatency = 20;
  std::string order = "scanline", jsonPath;
  std::vector<std::string> models = traversalDeviceNames<fx::GridUnit>();
  app.add_option("--scene", scenePath, "scene file (default: the bunny)");
  app.add_option("--width", width, "camera rays per row")->check(CLI::PositiveNumber);
  app.add_option("--height", height, "camera rays per column")->check(CLI::PositiveNumber);
  app.add_option("--repetitions", repetitions, "timed rounds (medians reported)")->check(CLI::PositiveNumber);
  app.add_option("--rays-in-flight", raysInFlight, "ray slots (0: all the unit was built with)");
  app.add_option("--mem-latency", memLatency, "memory latency in cycles")->check(CLI::PositiveNumber);
  app.add_option("--order", order, "ray order: scanline or shuffled")->check(CLI::IsMember({"scanline", "shuffled"}));
  app.add_option("--models", models, "models to run (default: every grid model of this build)");
  app.add_option("--json", jsonPath, "also write the figures as JSON");
  CLI11_PARSE(app, argc, argv);

  // ---- Rays and image, as the driver makes them.
  const Scene scene = loadScene(scenePath);
  const Quantizer quantizer(scene.bounds);
  std::vector<fx::QTriangle> triangles;
  for (uint32_t i = 0; i < scene.size(); ++i) triangles.push_back(quantizer.quantize(scene.triangles[i], i));
  CameraOptions camera;
  camera.width = width;
  camera.height = height;
  std::vector<fx::QRay> rays;
  const std::vector<Ray> cameraRays = frameScene(scene, camera).generateRays();
  for (uint32_t i = 0; i < cameraRays.size(); ++i) {
    if (auto r = quantizer.quantize(cameraRays[i], i)) rays.push_back(r->q);
  }
  if (order == "shuffled") {
    std::mt19937_64 rng(1);
    std::shuffle(rays.begin(), rays.end(), rng);
  }
  const fx::GridImage image = fx::buildGridImage(triangles, fx::chooseGridResolution(triangles));
  TraversalRunOptions options;
  options.memLatency = memLatency;
  options.raysInFlight = raysInFlight;
  fmt::print("{}: {} triangles, grid {}x{}x{}, {} camera rays ({}x{}, {} entered the lattice, {} order), "
             "mem latency {}, rays in flight {}\n",
             scenePath, triangles.size(), image.res[0], image.res[1], image.res[2], cameraRays.size(), width, height,
             rays.size(), order, memLatency, raysInFlight ? std::to_string(raysInFlight) : std::string("all"));

  // ---- Check pass: bit-exact traces, simulated figures.
  std::map<std::string, std::unique_ptr<GridDevice>> devices;
  for (const std::string& m : models) devices[m] = makeTraversalDevice<fx::GridUnit>(m);
  std::vector<fx::TraversalTrace> want, got;
  if (!devices.count("golden")) devices["golden"] = makeTraversalDevice<fx::GridUnit>("golden");
  devices["golden"]->run(image, rays, want, options);
  nlohmann::json json;
  json["scene"] = scenePath;
  json["rays"] = rays.size();
  json["order"] = order;
  json["mem_latency"] = memLatency;
  fmt::print("\n{:<20} {:>10} {:>10} {:>10} {:>10} {:>10} {:>11}\n", "model", "cycles", "steps/cyc", "steps/rdy",
             "tests/cyc", "isect busy", "cell reads");
  for (const std::string& m : models) {
    const TraversalRunStats s = devices[m]->run(image, rays, got, options);
    if (got != want) {
      fmt::print(stderr, "{}: traces differ from golden\n", m);
      return 1;
    }
    const double c = double(std::max<uint64_t>(s.cycles, 1));
    if (s.cycleAccurate) {
      fmt::print("{:<20} {:>10} {:>10.3f} {:>10.3f} {:>10.3f} {:>9.1f}% {:>11}\n", m, s.cycles,
                 double(s.steps) / c, double(s.steps) / double(std::max<uint64_t>(s.stepReadyCycles, 1)),
                 double(s.isectTests) / c, 100.0 * double(s.isectBusyCycles) / c, s.nodeReads);
    } else {
      fmt::print("{:<20} {:>10} {:>10} {:>10} {:>10} {:>10} {:>11}\n", m, "-", "-", "-", "-", "-", s.nodeReads);
    }
    json["models"][m]["cycles"] = s.cycles;
    json["models"][m]["steps"] = s.steps;
    json["models"][m]["step_ready_cycles"] = s.stepReadyCycles;
    json["models"][m]["isect_tests"] = s.isectTests;
    json["models"][m]["cell_reads"] = s.nodeReads;
  }

  // ---- Timed passes.
  std::map<std::string, std::vector<Sample>> samples;
  std::map<std::string, uint64_t> cycles;
  bench::rotatedRounds(repetitions, models.size(), [&](size_t i) {
    const std::string& m = models[i];
    samples[m].push_back(bench::timeSample([&] { cycles[m] = devices[m]->run(image, rays, got, options).cycles; }));
  });
  fmt::print("\nhost speed, median of {} rounds (wall clock; thread CPU time in brackets)\n", repetitions);
  fmt::print("{:<20} {:>9} {:>22} {:>24}\n", "model", "time s", "rays/s", "simulated cycles/s");
  for (const std::string& m : models) {
    std::vector<double> wall, cpu;
    for (const Sample& s : samples[m]) {
      wall.push_back(s.wall);
      cpu.push_back(s.cpu);
    }
    const double w = median(wall), c = median(cpu);
    const double n = double(rays.size());
    const std::string perCycle =
        cycles[m] ? fmt::format("{:>10.0f} [{:>9.0f}]", double(cycles[m]) / w, double(cycles[m]) / c) : "-";
    fmt::print("{:<20} {:>9.3f} {:>10.0f} [{:>9.0f}] {:>24}\n", m, w, n / w, n / c, perCycle);
    json["models"][m]["wall_s"] = w;
    json["models"][m]["cpu_s"] = c;
    json["models"][m]["rays_per_s"] = n / w;
    json["models"][m]["rays_per_cpu_s"] = n / c;
  }
  if (!jsonPath.empty()) {
    std::ofstream out(jsonPath);
    out << json.dump(2) << "\n";
  }
  return 0;
}
