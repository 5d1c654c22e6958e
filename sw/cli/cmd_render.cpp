// lancer render: a shaded image from the reference tracer, so a person can look.
#include <fmt/format.h>

#include "cli/options.h"
#include "ref/shade.h"
#include "ref/trace.h"

namespace lancer::cli {

void addRenderCommand(CLI::App& app) {
  struct Args {
    TracerArgs tracer;
    CameraArgs camera;
    std::string out = "lancer.png";
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("render", "Render a shaded image with the reference tracer");
  args->tracer.add(*cmd);
  args->camera.add(*cmd);
  cmd->add_option("--out", args->out, "PNG file to write")->capture_default_str();
  cmd->callback([args] {
    const Scene scene = args->tracer.scene.load();
    double buildSeconds = 0;
    const auto accel = args->tracer.build(scene, &buildSeconds);
    const PinholeCamera camera = frameScene(scene, args->camera.resolve());
    const std::vector<Ray> rays = camera.generateRays();
    const TracedRays traced = traceTimed("render", *accel, rays);
    writePng(shadeHits(scene, rays, traced.hits, camera.width(), camera.height()), args->out);
    fmt::print("render: {} ({} triangles), {} {}x{}, {} of {} rays hit, {:.3f} s -> {}\n", scene.name,
               scene.size(), accel->name(), camera.width(), camera.height(), traced.hitCount, rays.size(),
               traced.seconds, args->out);
    nlohmann::json report = tracerReport("render", scene, *accel, rays.size(), traced, buildSeconds);
    report["width"] = camera.width();
    report["height"] = camera.height();
    report["image"] = args->out;
    writeReport(args->tracer.report, report);
  });
}

}  // namespace lancer::cli
