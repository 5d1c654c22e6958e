// lancer render: a shaded image from the reference tracer, so a person can look.
#include <fmt/format.h>

#include "cli/options.h"
#include "ref/shade.h"
#include "ref/trace.h"

namespace lancer::cli {

void addRenderCommand(CLI::App& app) {
  struct Args {
    SceneOptions scene;
    CameraArgs camera;
    AccelArgs accel;
    std::string out = "lancer.png";
    std::string report;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("render", "Render a shaded image with the reference tracer");
  args->scene.add(*cmd);
  args->camera.add(*cmd);
  args->accel.add(*cmd, {"grid", "octree", "bvh", "embree"});
  cmd->add_option("--out", args->out, "PNG file to write")->capture_default_str();
  cmd->add_option("--report", args->report, "JSON report file");
  cmd->callback([args] {
    const Scene scene = args->scene.load();
    const PinholeCamera camera = frameScene(scene, args->camera.resolve());
    double buildSeconds = 0;
    const auto accel = buildAccel(args->accel.accel, scene, args->accel.options, &buildSeconds);
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
    writeReport(args->report, report);
  });
}

}  // namespace lancer::cli
