// lancer render: a shaded image from the reference tracer, so a person can look.
#include <chrono>

#include <fmt/format.h>

#include "cli/options.h"
#include "common/progress.h"
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
    TraversalStats stats;
    const auto start = std::chrono::steady_clock::now();
    Progress progress("render", rays.size());
    const auto hits = traceRays(*accel, rays, &stats, [&](size_t n) { progress.advance(n); });
    progress.finish();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writePng(shadeHits(scene, rays, hits, camera.width(), camera.height()), args->out);
    size_t hitCount = 0;
    for (const auto& h : hits) hitCount += h.has_value();
    fmt::print("render: {} ({} triangles), {} {}x{}, {} of {} rays hit, {:.3f} s -> {}\n", scene.name,
               scene.size(), accel->name(), camera.width(), camera.height(), hitCount, rays.size(), seconds,
               args->out);
    writeReport(args->report, {{"command", "render"},
                               {"scene", scene.name},
                               {"triangles", scene.size()},
                               {"accel", accel->name()},
                               {"width", camera.width()},
                               {"height", camera.height()},
                               {"rays", rays.size()},
                               {"hits", hitCount},
                               {"build_seconds", buildSeconds},
                               {"trace_seconds", seconds},
                               {"nodes_visited", stats.nodesVisited},
                               {"triangle_tests", stats.triangleTests},
                               {"image", args->out}});
  });
}

}  // namespace lancer::cli
