#include "cli/options.h"

#include <chrono>
#include <fstream>
#include <limits>

#include <fmt/format.h>

#include "common/error.h"
#include "common/progress.h"
#include "golden/units.h"
#include "oracle/make_accel.h"
#include "ref/trace.h"

namespace lancer::cli {

namespace {

std::optional<glm::vec3> toVec3(const std::vector<float>& v) {
  if (v.empty()) return std::nullopt;
  return glm::vec3(v[0], v[1], v[2]);
}

void addVec3(CLI::App& app, const std::string& name, std::vector<float>& into, const std::string& help) {
  app.add_option(name, into, help)->delimiter(',')->expected(3)->type_name("X,Y,Z");
}

}  // namespace

void SceneOptions::add(CLI::App& app) {
  app.add_option("--scene", scene, fmt::format("Scene file: {}", kSceneFormats))->capture_default_str();
  app.add_option("--subdivide", subdivide,
                 "Split every triangle into 4, this many times (large meshes for benchmarks)")
      ->check(CLI::Range(0, 6));
  app.add_option_function<std::string>(
         "--quadrics",
         [this](const std::string& form) { quadrics = form == "native" ? QuadricForm::Native : QuadricForm::Tessellate; },
         "NFF spheres and cones: native (quadrics: rt_quadric beside rt_isect in every unit and model, the "
         "reference structures, embree) or tessellate (triangles, for comparison)")
      ->check(CLI::IsMember({"tessellate", "native"}))
      ->default_str(toString(quadrics));
}

Scene SceneOptions::load() const {
  Scene loaded = loadScene(scene, quadrics);
  for (const std::string& warning : loaded.warnings) fmt::print(stderr, "warning: {}\n", warning);
  return subdivide ? lancer::subdivide(loaded, subdivide) : loaded;
}

void CameraArgs::add(CLI::App& app) {
  addVec3(app, "--eye", eye, "Camera position (default: auto-framed from the scene)");
  addVec3(app, "--look-at", target, "Point the camera looks at");
  addVec3(app, "--up", up, "Camera up vector (default 0,1,0)");
  app.add_option("--fov", fov, "Vertical field of view in degrees (default 40, or the scene's)");
  app.add_option("--width", width, "Image width in pixels")->capture_default_str();
  app.add_option("--height", height, "Image height in pixels")->capture_default_str();
}

CameraOptions CameraArgs::resolve() const {
  CameraOptions options;
  options.eye = toVec3(eye);
  options.target = toVec3(target);
  options.up = toVec3(up);
  options.fovYDegrees = fov;
  options.width = width;
  options.height = height;
  return options;
}

void TracerArgs::add(CLI::App& app) {
  scene.add(app);
  accel.add(app, {"grid", "octree", "bvh", "embree"});
  app.add_option("--report", report, "JSON report file");
}

std::unique_ptr<Accel> TracerArgs::build(const Scene& loaded, double* buildSeconds) const {
  return buildAccel(accel.accel, loaded, accel.options, buildSeconds);
}

void AccelArgs::add(CLI::App& app, const std::vector<std::string>& allowed) {
  app.add_option("--accel", accel, "Acceleration structure")
      ->check(CLI::IsMember(allowed))
      ->capture_default_str();
  fx::forEachTraversalUnit([&](auto unit) {
    for (const fx::BuildOption& o : decltype(unit)::buildOptions()) {
      if (!o.shapesReference) continue;
      const ReferenceBuildOption* reference = findReferenceBuildOption(o.field);
      addBuildOption(app, o, reference ? reference->help : o.help, reference ? reference->max : o.max, options);
    }
  });
}

void addBuildOption(CLI::App& app, const fx::BuildOption& option, const std::string& help, int max,
                    AccelOptions& into) {
  const int least = option.positive ? 1 : 0;
  app.add_option_function<int>(
      option.flag,
      [flag = option.flag, field = option.field, least, max, &into](int value) {
        if (value < least || value > max) {
          throw InputError(max == std::numeric_limits<int>::max()
                               ? fmt::format("{} {}: must be {} or more", flag, value, least)
                               : fmt::format("{} {}: must lie in {}..{}", flag, value, least, max));
        }
        into.*field = value;
      },
      help);
}

void EffectsArgs::add(CLI::App& app, CLI::Option* needs) {
  std::vector<CLI::Option*> added = {
      app.add_option("--effects", effects,
                     "Ray classes to trace, comma-separated: primary,shadow,reflection,refraction "
                     "(default: all the scene calls for)")
          ->delimiter(','),
      app.add_option("--max-depth", maxDepth, "Deepest ray tree; the eye ray has depth 1 (SPD rule 7)")
          ->capture_default_str(),
      app.add_option("--light-samples", lightSamples, "Shadow rays per emissive triangle per hit (area lights)")
          ->capture_default_str(),
      app.add_option("--sampling", sampling,
                     "Eye rays at pixel centers (WxH) or pixel corners ((W+1)x(H+1), averaged 4 to a pixel, "
                     "as the SPD counts)")
          ->capture_default_str()};
  if (needs) {
    for (CLI::Option* o : added) o->needs(needs);
  }
}

void RaySource::add(CLI::App& app) {
  app.add_option("--rays", raysFile, "Rays file (see traces/README.md); default: camera rays");
  camera.add(app);
}

void writeReport(const std::string& path, const nlohmann::json& report) {
  if (path.empty()) return;
  std::ofstream out(path);
  out << report.dump(2) << "\n";
  if (!out) throw InputError(fmt::format("{}: cannot write report", path));
}

std::unique_ptr<Accel> buildAccel(const std::string& kind, const Scene& scene, const AccelOptions& options,
                                  double* seconds) {
  const auto start = std::chrono::steady_clock::now();
  auto accel = makeAccel(parseAccelKind(kind), scene, options);
  if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return accel;
}

TracedRays traceTimed(const char* command, const Accel& accel, std::span<const Ray> rays) {
  TracedRays out;
  const auto start = std::chrono::steady_clock::now();
  Progress progress(command, rays.size());
  out.hits = traceRays(accel, rays, &out.stats, [&](size_t n) { progress.advance(n); });
  progress.finish();
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const auto& h : out.hits) out.hitCount += h.has_value();
  return out;
}

nlohmann::json tracerReport(const char* command, const Scene& scene, const Accel& accel, size_t rays,
                            const TracedRays& traced, double buildSeconds) {
  return {{"command", command},
          {"scene", scene.name},
          {"scene_numbers", toString(scene.numbers)},
          {"triangles", scene.size()},
          {"accel", accel.name()},
          {"rays", rays},
          {"hits", traced.hitCount},
          {"build_seconds", buildSeconds},
          {"trace_seconds", traced.seconds},
          {"nodes_visited", traced.stats.nodesVisited},
          {"triangle_tests", traced.stats.triangleTests}};
}

}  // namespace lancer::cli

#include "scene/rays_file.h"

namespace lancer::cli {

Rays loadRays(const RaySource& source, const Scene& scene) {
  Rays out;
  if (source.fromCamera()) {
    out.camera = frameScene(scene, source.camera.resolve());
    out.rays = out.camera->generateRays();
    out.origin = "camera";
  } else {
    out.rays = readRaysFile(source.raysFile);
    out.origin = source.raysFile;
  }
  return out;
}

void ChipArgs::add(CLI::App& app, JobConfig& job) {
  const auto opt = [&app](const char* name, auto& value, const char* what) {
    return app.add_option(name, value, what)->capture_default_str()->group("Chip (docs/chip.md)");
  };
  opt("--units", job.units, "Traversal units sharing the memory system, 1..64");
  opt("--memory", memory, "Memory system: fixed (latency and jitter only) or hierarchy (L1s, L2, DRAM)");
  opt("--l1-kib", job.memory.l1.kib, "hierarchy: KiB of each of a unit's three L1s (node, index, triangle)");
  opt("--l1-ways", job.memory.l1.ways, "hierarchy: L1 ways");
  opt("--l1-line-bytes", job.memory.l1.lineBytes, "hierarchy: line size of every level");
  opt("--l1-mshrs", job.memory.l1.mshrs, "hierarchy: lines in flight per L1");
  opt("--l1-latency", job.memory.l1.hitLatency, "hierarchy: L1 hit latency, cycles");
  opt("--l2-kib", job.memory.l2.kib, "hierarchy: KiB of the shared L2");
  opt("--l2-ways", job.memory.l2.ways, "hierarchy: L2 ways");
  opt("--l2-banks", job.memory.l2.banks, "hierarchy: L2 banks (one lookup per cycle each)");
  opt("--l2-latency", job.memory.l2.latency, "hierarchy: L2 latency, cycles");
  opt("--l2-mshrs", job.memory.l2.mshrs, "hierarchy: lines in flight to DRAM per L2 bank");
  opt("--dram-gbps", job.memory.dram.gbps, "hierarchy: DRAM bandwidth, GB/s");
  opt("--dram-latency-ns", job.memory.dram.latencyNs, "hierarchy: DRAM latency, ns");
  opt("--dram-channels", job.memory.dram.channels, "hierarchy: DRAM channels (lines interleaved)");
  opt("--dram-queue", job.memory.dram.queueDepth, "hierarchy: requests queued per DRAM channel");
  opt("--dispatch-batch", job.dispatchBatch, "Consecutive rays the dispatcher hands a unit at once");
  opt("--schedule", schedule,
      "The order the dispatcher hands a wave's rays out: fifo (as they come), sorted (by origin, then direction "
      "octant) or treelet (the BVH unit sets walks aside at treelet blocks, ray queues hand them out block by "
      "block; needs --bvh-treelet-bytes; docs/scheduling.md)");
  opt("--queue-kib", job.queues.kib, "treelet: KiB of the on-chip ray queue memory (beyond it, walks wait in DRAM)");
  opt("--queue-bytes-per-cycle", job.queues.bytesPerCycle, "treelet: the ray queue memory's read and write port width");
  opt("--queue-launch-below", job.queues.launchBelow,
      "treelet: launch fresh rays while the queue memory is less full than this fraction, else work on the fullest queue");
  opt("--host-threads", job.hostThreads, "Host threads clocking the units (0: one per core, at most one per unit; docs/chip.md)");
}

void ChipArgs::apply(JobConfig& job) const {
  job.memory.kind = mem::parseMemoryKind(memory);
  job.schedule = parseSchedule(schedule);
}

std::string ChipArgs::replayOptions(const JobConfig& job) {
  std::string out;
  if (job.units != 1) out += fmt::format(" --units {}", job.units);
  if (job.schedule != Schedule::Fifo) out += fmt::format(" --schedule {}", toString(job.schedule));
  if (job.schedule == Schedule::Treelet) {
    out += fmt::format(" --queue-kib {} --queue-bytes-per-cycle {} --queue-launch-below {:g}", job.queues.kib,
                       job.queues.bytesPerCycle, job.queues.launchBelow);
  }
  if (job.memory.kind == mem::MemoryKind::Fixed) return out;
  const mem::MemoryConfig& m = job.memory;
  return out + fmt::format(" --memory hierarchy --l1-kib {} --l1-ways {} --l1-line-bytes {} --l1-mshrs {} --l1-latency {} "
                           "--l2-kib {} --l2-ways {} --l2-banks {} --l2-latency {} --l2-mshrs {} --dram-gbps {:g} "
                           "--dram-latency-ns {:g} --dram-channels {} --dram-queue {}",
                           m.l1.kib, m.l1.ways, m.l1.lineBytes, m.l1.mshrs, m.l1.hitLatency, m.l2.kib, m.l2.ways,
                           m.l2.banks, m.l2.latency, m.l2.mshrs, m.dram.gbps, m.dram.latencyNs, m.dram.channels,
                           m.dram.queueDepth);
}

}  // namespace lancer::cli
