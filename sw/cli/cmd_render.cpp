// lancer render: a shaded image from the reference tracer, so a person can look.
// With --whitted, the SPD's classical Whitted tracer (docs/effects.md): the
// effects plan, shadow, reflection and refraction rays in waves, the SPD counts.
#include <chrono>

#include <fmt/format.h>

#include "cli/options.h"
#include "effects/ref_tracer.h"
#include "effects/whitted.h"
#include "ref/shade.h"
#include "ref/trace.h"

namespace lancer::cli {

namespace {

void renderWhitted(const Scene& scene, const Accel& accel, const PinholeCamera& camera, const EffectsArgs& effects,
                   const std::string& out, nlohmann::json& report) {
  const EffectsPlan plan = planEffects(scene, effects.options());
  const Sampling sampling = effects.parsedSampling();
  fmt::print("{}", plan.describe());
  const std::vector<Ray> eye = camera.generateRays(sampling);
  RefWaveTracer tracer(scene, accel);
  const auto start = std::chrono::steady_clock::now();
  const WhittedResult result = traceWhitted(scene, plan, eye, tracer, [&](int generation, size_t rays) {
    fmt::print("  wave {}: {} rays\n", generation, rays);
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writePng(samplesToImage(result.samples, camera.width(), camera.height(), sampling), out);
  fmt::print(
      "whitted: {} ({}), {} {}x{} at pixel {}: eye hit rays {}, reflect rays {}, refract rays {} "
      "({} total internal reflections), shadow rays {} ({} blocked), self-hits {}, {} waves, {:.3f} s -> {}\n",
      scene.name, scene.primitivesText(), accel.name(), camera.width(), camera.height(), toString(sampling),
      result.eyeHitRays, result.reflectRays, result.refractRays, result.totalInternalReflections,
      result.shadowRays, result.shadowRaysBlocked, result.selfHits, result.waveRays.size(), seconds, out);
  report = result.toJson();
  for (int c = 0; c < kWhittedClassCount; ++c) {
    const RayClass cls = RayClass(c);
    auto& j = report["classes"][std::string(toString(cls))];
    j["intersection_tests"] = tracer.stats(cls).triangleTests;
    j["nodes_visited"] = tracer.stats(cls).nodesVisited;
    j["host_seconds"] = tracer.seconds(cls);
  }
  report["command"] = "render";
  report["whitted"] = true;
  report["scene"] = scene.name;
  report["triangles"] = scene.size();
  report["accel"] = accel.name();
  report["plan"] = plan.toJson();
  report["sampling"] = toString(sampling);
  report["eye_rays"] = eye.size();
  report["origin_offset"] = tracer.offset();
  report["excluded_origin_hits"] = tracer.excludedOriginHits();
  report["trace_seconds"] = seconds;
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  struct Args {
    TracerArgs tracer;
    CameraArgs camera;
    EffectsArgs effects;
    bool whitted = false;
    std::string out = "lancer.png";
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("render", "Render a shaded image with the reference tracer");
  args->tracer.add(*cmd);
  args->camera.add(*cmd);
  CLI::Option* whitted = cmd->add_flag(
      "--whitted", args->whitted,
      "The SPD's classical Whitted tracer: shadow, reflection and refraction rays as the scene calls for");
  args->effects.add(*cmd, whitted);
  cmd->add_option("--out,--image", args->out, "PNG file to write")->capture_default_str();
  cmd->callback([args] {
    const Scene scene = args->tracer.scene.load();
    double buildSeconds = 0;
    const auto accel = args->tracer.build(scene, &buildSeconds);
    const PinholeCamera camera = frameScene(scene, args->camera.resolve());
    nlohmann::json report;
    if (args->whitted) {
      renderWhitted(scene, *accel, camera, args->effects, args->out, report);
      report["build_seconds"] = buildSeconds;
    } else {
      const std::vector<Ray> rays = camera.generateRays();
      const TracedRays traced = traceTimed("render", *accel, rays);
      writePng(shadeHits(scene, rays, traced.hits, camera.width(), camera.height()), args->out);
      fmt::print("render: {} ({}), {} {}x{}, {} of {} rays hit, {:.3f} s -> {}\n", scene.name,
                 scene.primitivesText(), accel->name(), camera.width(), camera.height(), traced.hitCount, rays.size(),
                 traced.seconds, args->out);
      report = tracerReport("render", scene, *accel, rays.size(), traced, buildSeconds);
    }
    report["width"] = camera.width();
    report["height"] = camera.height();
    report["image"] = args->out;
    writeReport(args->tracer.report, report);
  });
}

}  // namespace lancer::cli
