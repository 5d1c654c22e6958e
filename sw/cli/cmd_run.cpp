// lancer run: rays from the reference tracer through a model of the hardware,
// checked bit for bit against the golden model.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <memory>
#include <numeric>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli/options.h"
#include "common/error.h"
#include "common/progress.h"
#include "driver/candidates.h"
#include "driver/clocks.h"
#include "driver/job.h"
#include "driver/report.h"
#include "driver/silicon.h"
#include "driver/traversal_job.h"
#include "driver/wave_tracer.h"
#include "cli/shards.h"
#include "common/pfm.h"
#include "effects/ao.h"
#include "effects/path.h"
#include "effects/integrator.h"
#include "effects/ref_tracer.h"
#include "effects/whitted.h"
#include "golden/bvh.h"
#include "golden/isect.h"
#include "golden/octree.h"
#include "golden/units.h"
#include "ref/bvh.h"
#include "ref/shade.h"
#include "ref/trace.h"
#include "scene/rays_file.h"

namespace lancer::cli {

namespace {

struct Args {
  SceneOptions scene;
  RaySource source;
  fx::UnitKind accel = fx::UnitKind::Isect;
  JobConfig job;
  ChipArgs chip;
  EffectsArgs effects;
  std::string integrator = "whitted";  // --integrator whitted|ao|path
  AoOptions ao;
  PathOptions path;
  uint64_t samplerSeed = 1;            // --sampler-seed: the integrators' sampler key
  std::string pfm;                     // --pfm: the linear image
  std::string refImage;                // --ref-image: the float reference's image
  std::string shard;                   // --shard I/N: a part of the frame (cli/shards.h)
  std::optional<double> clockMhz;  // --clock-mhz; else the estimated clock (driver/clocks.h)
  int posBits = fx::kPosBits;
  int dirBits = fx::kDirBits;
  std::string report, image, hits;
  std::string repro = "lancer-mismatch.rays";
  int64_t latticeMargin = kLatticeMarginUnits;
};

void writeHardwareHits(const std::string& path, const JobResult& job) {
  std::unique_ptr<FILE, int (*)(FILE*)> out(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!out) throw InputError(fmt::format("{}: cannot write hits file", path));
  fmt::print(out.get(), "ray,hit,prim,t,u,v,t_num,det,u_num,v_num\n");
  for (size_t i = 0; i < job.hits.size(); ++i) {
    const auto hit = sceneHit(job, i);
    if (!hit) {
      fmt::print(out.get(), "{},0,-1,inf,0,0,0x0,0x0,0x0,0x0\n", i);
      continue;
    }
    const fx::IsectResult& r = *job.hits[i];
    auto hex = [](fx::u128 v) {
      return uint64_t(v >> 64) ? fmt::format("0x{:x}{:016x}", uint64_t(v >> 64), uint64_t(v))
                               : fmt::format("0x{:x}", uint64_t(v));
    };
    fmt::print(out.get(), "{},1,{},{:.9g},{:.9g},{:.9g},{},{},{},{}\n", i, hit->prim, hit->t, hit->u, hit->v,
               hex(r.tNum), hex(r.det), hex(r.uNum), hex(r.vNum));
  }
  if (std::ferror(out.get())) throw InputError(fmt::format("{}: write failed", path));
}

// Counts print and serialize as integers, ratios as decimals (four digits).
bool isWhole(double v) { return v == std::floor(v) && std::fabs(v) < 1e15; }
std::string wholeOrShort(double v) { return isWhole(v) ? fmt::format("{}", int64_t(v)) : fmt::format("{:.4g}", v); }
nlohmann::json counterJson(double v) { return isWhole(v) ? nlohmann::json(int64_t(v)) : nlohmann::json(v); }

// The options of the hardware path that shape what it computes or how it is
// timed, as they would be typed: what a replay must repeat.
std::string unitOptions(const Args& args) {
  const JobConfig& job = args.job;
  std::string out;
  const auto add = [&out](const char* flag, int value) {
    if (value) out += fmt::format(" {} {}", flag, value);
  };
  fx::forEachTraversalUnit([&](auto unit) {
    for (const fx::BuildOption& o : decltype(unit)::buildOptions()) {
      if (job.accel.*o.field != AccelOptions{}.*o.field) add(o.flag, job.accel.*o.field);
    }
  });
  if (args.latticeMargin != kLatticeMarginUnits) out += fmt::format(" --lattice-margin {}", args.latticeMargin);
  if (args.accel != fx::UnitKind::Isect) {
    out += fmt::format(" --mem-latency {}", job.memLatency);
    add("--mem-jitter", job.memLatencyJitter);
    add("--rays-in-flight", job.raysInFlight);
    out += ChipArgs::replayOptions(job);
  }
  return out;
}

void checkFormats(const Args& args) {
  if (args.posBits != fx::kPosBits || args.dirBits != fx::kDirBits) {
    throw InputError(fmt::format(
        "the hardware in this build uses {}-bit positions and {}-bit directions, not {} and {}: "
        "configure a build with -DLANCER_POS_BITS={} -DLANCER_DIR_BITS={}",
        fx::kPosBits, fx::kDirBits, args.posBits, args.dirBits, args.posBits, args.dirBits));
  }
  if (!(args.job.stream.outputStallProbability >= 0.0 && args.job.stream.outputStallProbability < 1.0)) {
    throw InputError(fmt::format("--stall {} must lie in [0, 1)", args.job.stream.outputStallProbability));
  }
}

// The figures of one job against the float reference (the plain run).
void printReferenceComparison(const ReferenceComparison& cmp) {
  fmt::print("  vs float reference  {} rays differ ({} hit/miss, {} triangle); t error max {:.3f}, mean {:.4f} lattice units\n",
             cmp.disagreements, cmp.hitMissDiffers, cmp.primDiffers, cmp.maxTError, cmp.meanTError);
  if (cmp.arbiter.judged) {
    const ArbiterCounts& a = cmp.arbiter;
    fmt::print("  exact arbiter       reference {} correct, {} tie, {} rounding, {} wrong; "
               "hardware {} correct, {} tie, {} within its lattice bound, {} beyond\n",
               a.reference[0], a.reference[1], a.reference[2], a.reference[3], a.hardware[0], a.hardware[1],
               a.hardware[2], a.hardware[3]);
    if (a.firstHardwareBeyond) fmt::print("  first ray beyond the hardware's bound: {}\n", *a.firstHardwareBeyond);
    if (a.firstReferenceWrong) fmt::print("  first ray the reference got wrong: {}\n", *a.firstReferenceWrong);
  }
}

// An answer beyond the hardware's documented bound is wrong, as a mismatch is:
// the run fails (after its report is written).
void failBeyondBound(uint64_t beyond, std::string_view what) {
  if (beyond) {
    throw CheckFailed(fmt::format("the exact arbiter puts the hardware's answer beyond its lattice bound on {} {}",
                                  beyond, what));
  }
}

void failMismatches(const Args& args, uint64_t mismatches, std::string_view what) {
  if (mismatches) {
    throw CheckFailed(
        fmt::format("model {} disagrees with the golden model on {} {}", args.job.model, mismatches, what));
  }
}

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// What every report of lancer run starts with: the command, the scene, the
// path and model, the formats, the clock and where it came from.
// A chip run's area and energy at the library's node, or why there are none.
void printSilicon(const RunClock& clock, const ChipFigures& chip, uint64_t cycles, uint64_t rays) {
  if (const auto si = chipSilicon(clock, chip, cycles, rays)) {
    fmt::print("{}", si->summary());
  } else {
    fmt::print("  silicon             no standard-cell figures of this unit at {}/{} (scripts/silicon, "
               "scripts/clock-table --silicon)\n",
               clock.posBits, clock.dirBits);
  }
}

nlohmann::json reportHeader(const Args& args, const Scene& scene, const RunClock& clock) {
  const Scene::PrimitiveCounts kinds = scene.primitivesByKind();
  return {{"command", "run"},         {"scene", scene.name},          {"scene_numbers", toString(scene.numbers)}, {"triangles", scene.size()},
          {"primitives", {{"triangles", kinds.triangles}, {"spheres", kinds.spheres}, {"cones", kinds.cones}}},
          {"quadrics", toString(args.scene.quadrics)},
          {"accel", toString(args.accel)}, {"model", args.job.model}, {"pos_bits", fx::kPosBits},
          {"dir_bits", fx::kDirBits},  {"clock_mhz", clock.mhz},      {"clock_source", clock.toJson()}};
}

// The SPD counts of a Whitted run, keyed as in the report.
std::vector<std::pair<const char*, uint64_t>> spdCounts(const WhittedResult& r) {
  return {{"eye_hit_rays", r.eyeHitRays},   {"reflect_rays", r.reflectRays},
          {"refract_rays", r.refractRays},  {"shadow_rays", r.shadowRays},
          {"shadow_rays_blocked", r.shadowRaysBlocked}, {"self_hits", r.selfHits}};
}

// Every figure of a run of waves (the Whitted loop, ambient occlusion): what
// the hardware did per class, against the float reference, on the chip; the
// summary and the report are both written from it. The integrator's own
// lines and keys come from its caller.
struct WaveRunFigures {
  const Args& args;
  const RunClock& clock;
  const Scene& scene;
  Sampling sampling;
  const PinholeCamera& camera;
  size_t eyeRays;
  const HardwareWaveTracer& tracer;
  std::vector<ClassKey> classes;   // the classes to report, in order
  std::vector<uint64_t> waveRays;  // the rays of each wave on the hardware
  double hostSeconds;

  double clockHz() const { return clock.hz(); }
  uint64_t cycles() const {
    uint64_t total = 0;
    for (const ClassKey cls : tracer.classes()) total += tracer.stats(cls).cycles;
    return total;
  }
  uint64_t allWaveRays() const { return std::accumulate(waveRays.begin(), waveRays.end(), uint64_t(0)); }

  // `integratorLines` prints what only the integrator knows, after the classes.
  void print(const std::function<void()>& integratorLines) const {
    fmt::print("run: {} ({}), {} {} samples {}x{}, model {}, accel {}, formats pos {} / dir {} bits\n",
               scene.name, scene.primitivesText(), eyeRays, toString(sampling), camera.width(), camera.height(),
               args.job.model, toString(args.accel), fx::kPosBits, fx::kDirBits);
    fmt::print("  clock               {}\n", clock.describe());
    printStructure();
    printClasses();
    printComparisons();
    printAnyHitSaving();
    integratorLines();
    fmt::print("  host                {:.2f} s in all; simulated {:.1f} us at {:g} MHz for {} cycles\n", hostSeconds,
               double(cycles()) / clockHz() * 1e6, clock.mhz, cycles());
    if (const auto c = chip()) {
      fmt::print("{}", c->summary(cycles(), allWaveRays(), clockHz()));
      printSilicon(clock, *c, cycles(), allWaveRays());
    }
    fmt::print("  bit-exact vs golden {} rays in {} waves, {} mismatches\n", allWaveRays(), waveRays.size(),
               tracer.mismatches());
  }

  // The chip's figures over every class.
  std::optional<ChipFigures> chip() const {
    std::optional<ChipFigures> all;
    for (const ClassKey cls : tracer.classes()) {
      const auto& mine = tracer.stats(cls).chip;
      if (!mine) continue;
      if (all) {
        *all += *mine;
      } else {
        all = mine;
      }
    }
    return all;
  }

  // The structure the unit walks, as built for the scene.
  void printStructure() const {
    const std::vector<JobCounter> figures = tracer.structure();
    if (figures.empty()) return;
    std::vector<std::string> items;
    for (const JobCounter& c : figures) items.push_back(fmt::format("{} {}", c.label, wholeOrShort(c.value)));
    fmt::print("  structure           {}\n", fmt::join(items, ", "));
  }

  // What the hardware did per ray class.
  void printClasses() const {
    fmt::print("  {:<11} {:>9} {:>9} {:>11} {:>10} {:>11} {:>11} {:>10}\n", "class", "rays", "hits", "tests",
               "steps", "cycles", "sim us", "mismatch");
    for (const ClassKey cls : classes) {
      const ClassHardwareStats& s = tracer.stats(cls);
      fmt::print("  {:<11} {:>9} {:>9} {:>11} {:>10} {:>11} {:>11.1f} {:>10}\n", toString(cls), s.rays, s.hits,
                 s.intersectionTests, s.steps, s.cycles, double(s.cycles) / clockHz() * 1e6, s.mismatches);
    }
  }

  // Each class against the float reference on the very rays the hardware traced.
  void printComparisons() const {
    fmt::print("  {:<11} {:>9} {:>9} {:>9}   {:<34} {}\n", "class", "vs ref", "hit/miss", "triangle",
               "arbiter: reference correct/tie/rnd/wrong", "hardware correct/tie/bound/beyond");
    for (const ClassKey cls : classes) {
      const ReferenceComparison& cmp = tracer.comparison(cls);
      const ArbiterCounts& a = cmp.arbiter;
      fmt::print("  {:<11} {:>9} {:>9} {:>9}   {:<34} {}\n", toString(cls), cmp.disagreements, cmp.hitMissDiffers,
                 cmp.primDiffers,
                 fmt::format("{}/{}/{}/{}", a.reference[0], a.reference[1], a.reference[2], a.reference[3]),
                 fmt::format("{}/{}/{}/{}", a.hardware[0], a.hardware[1], a.hardware[2], a.hardware[3]));
    }
    if (const auto& b = tracer.firstBeyond()) fmt::print("  first ray beyond the hardware's bound: {}", b->details);
    if (!tracer.cycleAccurate()) fmt::print("  (golden model: no cycle timing)\n");
  }

  // What the any-hit rays (shadow, occlusion) saved by stopping at their first hit (traversal units).
  void printAnyHitSaving() const {
    if (args.accel == fx::UnitKind::Isect) return;
    for (const ClassKey cls : {ClassKey(RayClass::Shadow), ClassKey(RayClass::Ao)}) {
      const ClassHardwareStats& s = tracer.stats(cls);
      if (!s.rays) continue;
      fmt::print("  any-hit saving      {} rays took {} steps and {} tests; as closest-hit rays {} and {} ({:.1f}% "
                 "fewer steps)\n",
                 toString(cls), s.steps, s.intersectionTests, s.closestHitSteps, s.closestHitTests,
                 s.closestHitSteps ? 100.0 * (1.0 - double(s.steps) / double(s.closestHitSteps)) : 0.0);
    }
  }

  // The secondary origins' fixes.
  void printOrigins() const {
    if (tracer.sideFlips()) {
      fmt::print("  {} secondary origins moved to the other side of their triangle or past their quadric (the "
                 "lattice ray would have met it again)\n",
                 tracer.sideFlips());
    }
    if (tracer.originsOutside()) {
      fmt::print("  {} secondary rays left the lattice cube at their origin (not traced)\n", tracer.originsOutside());
    }
  }

  nlohmann::json toJson() const {
    nlohmann::json perClass;
    for (const ClassKey cls : classes) {
      nlohmann::json& c = perClass[toString(cls)] = tracer.stats(cls).toJson(clockHz());
      c.update(lancer::toJson(tracer.comparison(cls)));
    }
    nlohmann::json report = reportHeader(args, scene, clock);
    report.update({{"sampling", toString(sampling)},
                   {"width", camera.width()},
                   {"height", camera.height()},
                   {"eye_rays", eyeRays},
                   {"classes", perClass},
                   {"cycles", cycles()},
                   {"cycle_accurate", tracer.cycleAccurate()},
                   {"clock_hz", clockHz()},
                   {"mismatches", tracer.mismatches()},
                   {"host_seconds", hostSeconds},
                   {"origin_offset_lattice_units", tracer.offsetUnits()},
                   {"origins_outside_lattice", tracer.originsOutside()},
                   {"secondary_side_flips", tracer.sideFlips()},
                   {"wave_rays", waveRays},
                   {"beyond_bound", tracer.beyondBound()}});
    nlohmann::json structure = nlohmann::json::object();
    for (const JobCounter& c : tracer.structure()) structure[c.key] = counterJson(c.value);
    report["structure"] = structure;
    if (const auto c = chip()) {
      report.update(c->toJson(cycles(), allWaveRays(), clockHz()));
      if (const auto si = chipSilicon(clock, *c, cycles(), allWaveRays())) report.update(si->toJson());
    }
    if (const auto& m = tracer.firstMismatch()) {
      report["first_mismatch"] = {{"generation", m->generation}, {"class", toString(m->cls)}, {"index", m->index},
                                  {"report", m->details}};
    }
    if (const auto& b = tracer.firstBeyond()) {
      report["first_beyond_bound"] = {{"generation", b->generation}, {"class", toString(b->cls)},
                                      {"index", b->index}, {"report", b->details}};
    }
    return report;
  }

  // Writes the report, then fails the run on a mismatch or an answer beyond the bound.
  void finish(const nlohmann::json& report) const {
    if (const auto& m = tracer.firstMismatch()) fmt::print(stderr, "{}", m->details);
    writeReport(args.report, report);
    failMismatches(args, tracer.mismatches(), "wave rays");
    failBeyondBound(tracer.beyondBound(), "wave rays");
  }
};

// The classes a Whitted plan traces, in the plan's order.
std::vector<ClassKey> plannedClasses(const EffectsPlan& plan) {
  std::vector<ClassKey> classes;
  for (int c = 0; c < kWhittedClassCount; ++c) {
    if (plan.has(RayClass(c))) classes.push_back(RayClass(c));
  }
  return classes;
}

// The wave lines of a run on a terminal.
WaveProgress waveLines(const Args& args) {
  return [&args](int generation, size_t n) {
    fmt::print("  wave {}: {} rays on {} {}\n", generation, n, toString(args.accel), args.job.model);
  };
}

// An effects run (docs/effects.md): the Whitted loop's waves through the
// hardware, every wave checked against the golden model bit for bit, and the
// same loop on the float reference tracer for the counts.
void runEffects(const Args& args, const RunClock& clock, const Scene& scene, const EffectsPlan& plan,
                const Quantizer& quantizer, std::chrono::steady_clock::time_point hostStart) {
  const Sampling sampling = args.effects.parsedSampling();
  const PinholeCamera camera = frameScene(scene, args.source.camera.resolve());
  const std::vector<Ray> eye = camera.generateRays(sampling);
  const Bvh reference(scene, AccelOptions{});
  HardwareWaveTracer tracer(args.accel, scene, quantizer, args.job, &reference);
  const WhittedResult hw = traceWhitted(scene, plan, eye, tracer, waveLines(args));
  RefWaveTracer refTracer(scene, reference);
  const WhittedResult ref = traceWhitted(scene, plan, eye, refTracer);
  const WaveRunFigures figures{args,   clock,   scene, sampling, camera, eye.size(), tracer, plannedClasses(plan),
                               hw.waveRays, secondsSince(hostStart)};
  figures.print([&] {
    fmt::print("  {:<20} {:>10} {:>10}\n", "SPD count", "hardware", "float ref");
    const auto hwCounts = spdCounts(hw), refCounts = spdCounts(ref);
    for (size_t k = 0; k < hwCounts.size(); ++k) {
      fmt::print("  {:<20} {:>10} {:>10}\n", hwCounts[k].first, hwCounts[k].second, refCounts[k].second);
    }
    figures.printOrigins();
  });
  if (!args.image.empty()) {
    writePng(samplesToImage(hw.samples, camera.width(), camera.height(), sampling), args.image);
    fmt::print("  image               {} (shaded from the model's hits)\n", args.image);
  }
  nlohmann::json report = figures.toJson();
  report.update({{"integrator", "whitted"},
                 {"plan", plan.toJson()},
                 {"total_internal_reflections", hw.totalInternalReflections},
                 {"refraction_rays_traced", hw.refractionsTraced}});
  for (const auto& [key, value] : spdCounts(hw)) report[key] = value;
  nlohmann::json refJson;
  for (const auto& [key, value] : spdCounts(ref)) refJson[key] = value;
  report["float_reference"] = refJson;
  figures.finish(report);
}

// A run of an integrator that samples (ambient occlusion, the path tracer;
// docs/incoherent.md): its waves through the hardware, each checked against
// the golden model bit for bit; the same waves on the float reference, and the
// image's error against it. `trace` runs the integrator on a tracer;
// `options` and `describe` are its report entry and its summary line.
// A shard (--shard I/N) traces its part of the frame's samples, keyed as in
// the whole frame, and leaves its samples beside its report for lancer merge.
using SampledTrace =
    std::function<IntegratorResult(std::span<const Ray>, WaveTracer&, const WaveProgress&, uint32_t firstSample)>;

void runSampled(const Args& args, const RunClock& clock, const Scene& scene, const Quantizer& quantizer,
                std::chrono::steady_clock::time_point hostStart, const SampledTrace& trace,
                const nlohmann::json& options, const std::string& describe) {
  const Sampling sampling = args.effects.parsedSampling();
  const PinholeCamera camera = frameScene(scene, args.source.camera.resolve());
  const std::vector<Ray> frame = camera.generateRays(sampling);
  const std::optional<cli::Shard> shard = args.shard.empty() ? std::nullopt : std::optional(cli::parseShard(args.shard));
  const auto [first, last] = shard ? cli::shardRange(*shard, frame.size()) : std::pair<size_t, size_t>(0, frame.size());
  const std::span<const Ray> eye = std::span(frame).subspan(first, last - first);
  const Bvh reference(scene, AccelOptions{});
  HardwareWaveTracer tracer(args.accel, scene, quantizer, args.job, &reference);
  const IntegratorResult hw = trace(eye, tracer, waveLines(args), uint32_t(first));
  RefWaveTracer refTracer(scene, reference);
  const IntegratorResult ref = trace(eye, refTracer, {}, uint32_t(first));
  const double mse = relativeMse(hw.samples, ref.samples);
  // The classes in a path's order: camera, the bounces, then the any-hit rays.
  std::vector<ClassKey> classes = tracer.classes();
  const auto rank = [](ClassKey k) { return std::pair(k.cls == RayClass::Shadow || k.cls == RayClass::Ao, k); };
  std::sort(classes.begin(), classes.end(), [&](ClassKey a, ClassKey b) { return rank(a) < rank(b); });
  const WaveRunFigures figures{args,   clock,   scene, sampling, camera, eye.size(), tracer, std::move(classes),
                               hw.waveRays, secondsSince(hostStart)};
  figures.print([&] {
    fmt::print("  {:<19} {}; image rel. MSE vs float reference {:.3g}; self-hits {}\n", args.integrator, describe,
               mse, hw.selfHits);
    figures.printOrigins();
  });
  nlohmann::json report = figures.toJson();
  report.update({{"integrator", args.integrator},
                 {args.integrator, options},
                 {"image_rel_mse", mse},
                 {"self_hits", hw.selfHits},
                 {"float_reference", ref.toJson()}});
  if (shard) {
    // What makes two shards parts of one run, for lancer merge.
    report["run_key"] = {{"scene", scene.name},          {"accel", toString(args.accel)},
                         {"model", args.job.model},      {"integrator", args.integrator},
                         {args.integrator, options},      {"width", camera.width()},
                         {"height", camera.height()},    {"sampling", toString(sampling)},
                         {"pos_bits", fx::kPosBits},     {"dir_bits", fx::kDirBits},
                         {"units", args.job.units},      {"memory", args.chip.memory},
                         {"schedule", toString(args.job.schedule)}};
    report["shard"] = {{"index", shard->index},   {"count", shard->count}, {"first_sample", first},
                       {"samples", last - first}, {"total_samples", frame.size()}};
    cli::writeShardSamples(cli::samplesFileOf(args.report), hw.samples, ref.samples);
    fmt::print("  shard               {}/{}: samples {}..{} of {} (samples in {})\n", shard->index, shard->count,
               first, last, frame.size(), cli::samplesFileOf(args.report));
    figures.finish(report);
    return;
  }
  if (!args.image.empty()) {
    writePng(samplesToImage(hw.samples, camera.width(), camera.height(), sampling), args.image);
    fmt::print("  image               {} (from the model's hits)\n", args.image);
  }
  if (!args.refImage.empty()) {
    writePng(samplesToImage(ref.samples, camera.width(), camera.height(), sampling), args.refImage);
    fmt::print("  reference image     {} (the same integrator on the float reference)\n", args.refImage);
  }
  if (!args.pfm.empty()) {
    writePfm(samplesToPixels(hw.samples, camera.width(), camera.height(), sampling), camera.width(), camera.height(),
             args.pfm);
    fmt::print("  linear image        {} (PFM)\n", args.pfm);
  }
  figures.finish(report);
}

// Every figure of a plain run (one job over camera or file rays): the summary
// and the report are both written from it.
struct RunFigures {
  const Args& args;
  const RunClock& clock;
  const Scene& scene;
  const Rays& rays;
  const JobResult& job;
  const ReferenceComparison& cmp;
  double hostSeconds;

  double clockHz() const { return clock.hz(); }
  double simulatedSeconds() const { return double(job.cycles) / clockHz(); }
  double testsPerCycle() const { return job.cycles ? double(job.intersectionTests) / double(job.cycles) : 0.0; }
  double testsPerSecond() const { return job.cycles ? double(job.intersectionTests) / simulatedSeconds() : 0.0; }
  double raysPerSecond() const { return job.cycles ? double(rays.rays.size()) / simulatedSeconds() : 0.0; }
  size_t inLattice() const { return size_t(std::count_if(job.rays.begin(), job.rays.end(), [](auto& r) { return r.has_value(); })); }
  size_t hits() const { return size_t(std::count_if(job.hits.begin(), job.hits.end(), [](auto& h) { return h.has_value(); })); }

  void print() const {
    fmt::print("run: {} ({}), {} rays from {}, model {}, accel {}, formats pos {} / dir {} bits\n",
               scene.name, scene.primitivesText(), rays.rays.size(), rays.origin, args.job.model, toString(args.accel),
               fx::kPosBits, fx::kDirBits);
    fmt::print("  clock               {}\n", clock.describe());
    if (job.cycleAccurate) {
      fmt::print("  intersection tests  {} in {} cycles ({:.4f} tests/cycle)\n", job.intersectionTests, job.cycles,
                 testsPerCycle());
      fmt::print("  simulated rate      {:.1f} M intersections/s, {:.2f} M rays/s at {:g} MHz ({:.1f}x the AR250's "
                 "80 M/s)\n",
                 testsPerSecond() / 1e6, raysPerSecond() / 1e6, clock.mhz, testsPerSecond() / 80e6);
    } else {
      fmt::print("  intersection tests  {} (golden model: no cycle timing{})\n", job.intersectionTests,
                 job.cycles ? fmt::format(", ideal pipeline {} cycles", job.cycles) : "");
    }
    for (const JobCounter& c : job.counters) {
      fmt::print("  {:<19} {}\n", c.label, wholeOrShort(c.value));
    }
    fmt::print("  host                {:.2f} s in all, {:.2f} s in the model ({:.0f} rays/s), {:.2f} s in golden\n",
               hostSeconds, job.modelSeconds, job.modelSeconds > 0 ? double(inLattice()) / job.modelSeconds : 0.0,
               job.goldenSeconds);
    if (job.chip) {
      fmt::print("{}", job.chip->summary(job.cycles, rays.rays.size(), clockHz()));
      printSilicon(clock, *job.chip, job.cycles, rays.rays.size());
    }
    fmt::print("  bit-exact vs golden {} rays ({} entered the lattice, {} hit), {} mismatches\n", rays.rays.size(),
               inLattice(), hits(), job.mismatchedRays);
    printReferenceComparison(cmp);
  }

  nlohmann::json toJson() const {
    nlohmann::json report = reportHeader(args, scene, clock);
    report.update({{"rays", rays.rays.size()},
                   {"rays_in_lattice", inLattice()},
                   {"rays_hit", hits()},
                   {"mismatches", job.mismatchedRays},
                   {"cycles", job.cycles},
                   {"cycle_accurate", job.cycleAccurate},
                   {"intersection_tests", job.intersectionTests},
                   {"tests_per_cycle", testsPerCycle()},
                   {"clock_hz", clockHz()},
                   {"intersections_per_second", testsPerSecond()},
                   {"rays_per_second", raysPerSecond()},
                   {"host_seconds", hostSeconds},
                   {"model_seconds", job.modelSeconds},
                   {"golden_seconds", job.goldenSeconds},
                   {"output_stall_probability", args.job.stream.outputStallProbability},
                   {"seed", args.job.stream.seed}});
    report.update(lancer::toJson(cmp));
    if (job.chip) {
      report.update(job.chip->toJson(job.cycles, rays.rays.size(), clockHz()));
      if (const auto si = chipSilicon(clock, *job.chip, job.cycles, rays.rays.size())) report.update(si->toJson());
    }
    for (const JobCounter& c : job.counters) {
      report[c.key] = counterJson(c.value);
    }
    return report;
  }
};

// InputError for a run the options make impossible, before any work.
void checkRunOptions(const Args& args) {
  checkFormats(args);
  const std::vector<std::string> models = modelsFor(args.accel);
  if (std::find(models.begin(), models.end(), args.job.model) == models.end()) {
    throw InputError(fmt::format("--model {}: the {} path has no such model (available: {})", args.job.model,
                                 toString(args.accel), fmt::join(models, ", ")));
  }
  if (args.accel == fx::UnitKind::Isect && (args.job.units != 1 || args.job.memory.kind != mem::MemoryKind::Fixed)) {
    throw InputError("--units and --memory hierarchy describe a chip of traversal units: they need --accel grid or "
                     "octree, not isect");
  }
  if (args.accel != fx::UnitKind::Isect) checkChipOptions(traversalOptionsOf(args.job));
  if (!args.job.dualNarrowBits.empty() && args.accel != fx::UnitKind::Isect) {
    throw InputError(fmt::format("--dual-precision models the intersection pipeline's front end: it needs --accel isect, "
                                 "not {}", toString(args.accel)));
  }
}

// The image and the hits file drawn from the model's hits, where asked for.
void writeHitOutputs(const Args& args, const Scene& scene, const Rays& rays, const JobResult& job) {
  if (!args.image.empty()) {
    if (!rays.camera) throw InputError("--image needs camera rays (no --rays file)");
    std::vector<std::optional<Hit>> hits(job.hits.size());
    for (size_t i = 0; i < hits.size(); ++i) hits[i] = sceneHit(job, i);
    writePng(shadeHits(scene, rays.rays, hits, rays.camera->width(), rays.camera->height()), args.image);
    fmt::print("  image               {} (drawn from the model's hits)\n", args.image);
  }
  if (!args.hits.empty()) writeHardwareHits(args.hits, job);
}

// The first failing ray (a mismatch, else an answer beyond the bound): printed
// with a one-ray rays file and the command that replays it, and added to the report.
void reportFirstFailure(const Args& args, const Scene& scene, const Rays& rays, const JobResult& job,
                        const ReferenceComparison& cmp, nlohmann::json& report) {
  const auto reproduce = [&](uint32_t ray, std::string_view what) {
    writeRaysFile(args.repro, {rays.rays[ray]}, fmt::format("ray {} of {}: {} reproducer", ray, rays.origin, what));
    return fmt::format("lancer run --scene {}{} --rays {} --model {} --accel {}{} --stall {} --seed {}", scene.name,
                       args.scene.subdivide ? fmt::format(" --subdivide {}", args.scene.subdivide) : "", args.repro,
                       args.job.model, toString(args.accel), unitOptions(args), args.job.stream.outputStallProbability,
                       args.job.stream.seed);
  };
  if (job.firstMismatch) {
    const MismatchReport& m = *job.firstMismatch;
    const std::string text = fmt::format("{}  replay: {}\n", m.details, reproduce(m.rayId, "mismatch"));
    fmt::print(stderr, "{}", text);
    report["first_mismatch"] = {{"ray", m.rayId}, {"report", text}, {"repro_rays", args.repro}};
  } else if (const auto beyond = cmp.arbiter.firstHardwareBeyond) {
    const std::string text = fmt::format("ray {}: the hardware's answer is beyond its lattice bound ({})\n  replay: {}\n",
                                         *beyond, cmp.arbiter.firstHardwareBeyondWhy, reproduce(*beyond, "beyond-bound"));
    fmt::print(stderr, "{}", text);
    report["first_beyond_bound"] = {{"ray", *beyond}, {"report", text}, {"repro_rays", args.repro}};
  }
}

void run(Args args) {
  args.chip.apply(args.job);
  checkRunOptions(args);
  const auto hostStart = std::chrono::steady_clock::now();
  const Scene scene = args.scene.load();
  // The slowest unit of the run: rt_quadric's too when the scene has quadrics.
  const RunClock clock = runClock(args.accel, args.clockMhz, !scene.quadrics.empty());
  args.job.memory.clockMhz = clock.mhz;  // DRAM's nanoseconds in the run's cycles
  const Quantizer quantizer(scene.bounds, args.latticeMargin);
  if (!args.shard.empty()) {
    cli::parseShard(args.shard);
    if (args.integrator == "whitted") {
      throw InputError("--shard: the Whitted loop's area-light samples follow the waves' order; shard an ao or path run");
    }
    if (args.report.empty()) throw InputError("--shard needs --report: lancer merge reads the shards' reports");
  }
  if (args.integrator != "whitted") {
    if (!args.source.fromCamera()) {
      throw InputError(fmt::format("--integrator {} traces from camera rays: it takes no --rays file", args.integrator));
    }
    args.ao.seed = args.path.seed = args.samplerSeed;
    args.path.maxDepth = args.effects.maxDepth;
    if (args.integrator == "ao") {
      checkAoOptions(args.ao);
      runSampled(args, clock, scene, quantizer, hostStart,
                 [&](std::span<const Ray> eye, WaveTracer& t, const WaveProgress& p, uint32_t first) {
                   return traceAo(scene, args.ao, eye, t, p, first);
                 },
                 args.ao.toJson(scene),
                 fmt::format("{} occlusion rays a hit within {:g}", args.ao.rays, args.ao.distanceFor(scene)));
    } else {
      checkPathOptions(args.path);
      runSampled(args, clock, scene, quantizer, hostStart,
                 [&](std::span<const Ray> eye, WaveTracer& t, const WaveProgress& p, uint32_t first) {
                   return tracePath(scene, args.path, eye, t, p, first);
                 },
                 args.path.toJson(),
                 fmt::format("{} paths a sample, depth {}, Russian roulette from bounce {}", args.path.spp,
                             args.path.maxDepth, args.path.rrDepth));
    }
    return;
  }
  const EffectsPlan plan = planEffects(scene, args.effects.options());
  fmt::print("{}", plan.describe());
  const bool secondary =
      plan.has(RayClass::Shadow) || plan.has(RayClass::Reflection) || plan.has(RayClass::Refraction);
  if (args.source.fromCamera() && (secondary || args.effects.parsedSampling() == Sampling::Corners)) {
    runEffects(args, clock, scene, plan, quantizer, hostStart);
    return;
  }
  if (secondary) fmt::print("  (rays from {}: primary rays only; effects need camera rays)\n", args.source.raysFile);
  const Rays rays = loadRays(args.source, scene);

  Progress progress(fmt::format("run {} {}", toString(args.accel), args.job.model), rays.rays.size());
  const JobResult job = runJob(args.accel, scene, rays.rays, quantizer, args.job, [&](size_t n) { progress.advance(n); });
  progress.finish();

  const Bvh reference(scene, AccelOptions{});
  const ReferenceComparison cmp = compareWithReference(scene, rays.rays, traceRays(reference, rays.rays), job, quantizer,
                                                         exactCandidates(reference, scene.bounds));
  const RunFigures figures{args, clock, scene, rays, job, cmp, secondsSince(hostStart)};
  figures.print();
  writeHitOutputs(args, scene, rays, job);
  nlohmann::json report = figures.toJson();
  reportFirstFailure(args, scene, rays, job, cmp, report);
  writeReport(args.report, report);
  failMismatches(args, job.mismatchedRays, "rays");
  failBeyondBound(cmp.arbiter.beyondBound(), "rays");
}

}  // namespace

void addRunCommand(CLI::App& app) {
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("run", "Run rays through a hardware model and check it bit for bit");
  args->scene.add(*cmd);
  args->source.add(*cmd);
  // Checked by name (the message lists the paths), then kept as fx::UnitKind.
  const std::vector<std::string> names = hardwarePathNames();
  cmd->add_option_function<std::string>(
         "--accel", [args](const std::string& name) { args->accel = parseHardwarePath(name); },
         fmt::format("Hardware path: isect (the host BVH feeding the intersection pipeline) or a traversal unit ({})",
                     fmt::join(names.begin() + 1, names.end(), ", ")))
      ->check(CLI::IsMember(names))
      ->default_str(std::string(toString(args->accel)));
  cmd->add_option("--model", args->job.model,
                  "Model of the hardware: golden, systemc (cycle models on value ports), rtl (Verilated), "
                  "rtl-systemc (Verilated in the SystemC kernel), systemc-pins (the cycle models on signals in the "
                  "kernel)")
      ->check(CLI::IsMember({"golden", "systemc", "rtl", "rtl-systemc", "systemc-pins"}))
      ->capture_default_str();
  cmd->add_option_function<double>(
      "--clock-mhz", [args](double mhz) { args->clockMhz = mhz; },
      "Clock of the simulated rates (default: the estimated clock of the slowest unit in the run at this build's "
      "widths, rtl/synth/clocks.json)");
  cmd->add_option("--pos-bits", args->posBits, "Expected position width (must match the build)");
  cmd->add_option("--dir-bits", args->dirBits, "Expected direction width (must match the build)");
  fx::forEachTraversalUnit([&](auto unit) {
    for (const fx::BuildOption& o : decltype(unit)::buildOptions()) {
      addBuildOption(*cmd, o, o.help, o.max, args->job.accel);
    }
  });
  cmd->add_option("--mem-latency", args->job.memLatency, "Memory latency of the traversal units, in cycles")
      ->capture_default_str();
  cmd->add_option("--mem-jitter", args->job.memLatencyJitter, "Random extra memory latency per read, 0..N cycles")
      ->capture_default_str();
  cmd->add_option("--rays-in-flight", args->job.raysInFlight, "Ray slots of the traversal unit (default: all built)");
  cmd->add_option("--stall", args->job.stream.outputStallProbability,
                  "Probability per cycle that the consumer stalls the unit's output")
      ->capture_default_str();
  cmd->add_option("--seed", args->job.stream.seed, "Seed of the stall pattern")->capture_default_str();
  cmd->add_option("--report", args->report, "JSON report file");
  cmd->add_option("--image", args->image, "PNG drawn from the model's own hits");
  cmd->add_option("--hits", args->hits, "CSV of the model's hits, with the raw fixed-point fields in hex");
  cmd->add_option("--wave", args->job.stream.wavePath, "FST waveform of the RTL (rtl model only; slow)");
  cmd->add_option("--dual-precision", args->job.dualNarrowBits,
                  "isect path: model a narrow front end at these widths (e.g. 8,10,12) and report the share of tests "
                  "it escalates to full width (docs/accuracy.md)")
      ->delimiter(',')
      ->check(CLI::Range(2, 24));
  args->effects.add(*cmd);
  cmd->add_option("--integrator", args->integrator,
                  "What the camera rays' hits spawn: whitted (the SPD's loop, --effects), ao (ambient occlusion: "
                  "--ao-rays any-hit segments a hit) or path (a path tracer: --spp, --max-depth, --rr-depth); "
                  "docs/incoherent.md")
      ->check(CLI::IsMember({"whitted", "ao", "path"}))
      ->capture_default_str();
  cmd->add_option("--ao-rays", args->ao.rays, "ao: occlusion rays a hit (1..4096)")->capture_default_str();
  cmd->add_option("--ao-distance", args->ao.distance,
                  "ao: their length in scene units (default: a tenth of the scene's diagonal)");
  cmd->add_option("--spp", args->path.spp, "path: paths a camera sample (1..65536)")->capture_default_str();
  cmd->add_option("--rr-depth", args->path.rrDepth, "path: the first bounce Russian roulette may end a path at")
      ->capture_default_str();
  cmd->add_option("--pfm", args->pfm, "ao, path: the linear image as PFM (the PNG of --image is tone-mapped)");
  cmd->add_option("--ref-image", args->refImage, "ao, path: the float reference's image (PNG), beside --image");
  cmd->add_option("--shard", args->shard,
                  "ao, path: trace shard I of N of the frame's camera samples (I/N); lancer merge joins the shards' "
                  "reports into the whole frame's, bit for bit");
  cmd->add_option("--sampler-seed", args->samplerSeed,
                  "Key of the integrators' counter-based sampler (the same rays for every model, unit count and "
                  "thread count)")
      ->capture_default_str();
  args->chip.add(*cmd, args->job);
  cmd->add_option("--lattice-margin", args->latticeMargin,
                  "Lattice units between the scene's bounds and the lattice cube's faces (0: the faces coincide, "
                  "and a closed object seen from outside shows its inside: docs/number-formats.md)")
      ->capture_default_str();
  cmd->add_option("--repro", args->repro, "Where a mismatch's reproducer rays file goes")->capture_default_str();
  cmd->callback([args] { run(*args); });
}

}  // namespace lancer::cli
