// lancer trace: closest hits of camera rays or a rays file, as CSV.
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "cli/options.h"
#include "common/error.h"
#include "ref/trace.h"

namespace lancer::cli {

namespace {

void writeHitsCsv(const std::string& path, const std::vector<std::optional<Hit>>& hits) {
  std::unique_ptr<FILE, int (*)(FILE*)> out(std::fopen(path.c_str(), "w"), &std::fclose);
  if (!out) throw InputError(fmt::format("{}: cannot write hits file", path));
  fmt::print(out.get(), "ray,hit,prim,t,u,v\n");
  for (size_t i = 0; i < hits.size(); ++i) {
    if (hits[i]) {
      fmt::print(out.get(), "{},1,{},{:.9g},{:.9g},{:.9g}\n", i, hits[i]->prim, hits[i]->t, hits[i]->u, hits[i]->v);
    } else {
      fmt::print(out.get(), "{},0,-1,inf,0,0\n", i);
    }
  }
  if (std::ferror(out.get())) throw InputError(fmt::format("{}: write failed", path));
}

}  // namespace

void addTraceCommand(CLI::App& app) {
  struct Args {
    TracerArgs tracer;
    RaySource source;
    std::string hits;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("trace", "Closest hits of rays with the reference tracer, as CSV");
  args->tracer.add(*cmd);
  args->source.add(*cmd);
  cmd->add_option("--hits", args->hits, "CSV file to write: ray,hit,prim,t,u,v")->required();
  cmd->callback([args] {
    const Scene scene = args->tracer.scene.load();
    double buildSeconds = 0;
    const auto accel = args->tracer.build(scene, &buildSeconds);
    const Rays rays = loadRays(args->source, scene);
    const TracedRays traced = traceTimed("trace", *accel, rays.rays);
    writeHitsCsv(args->hits, traced.hits);
    fmt::print("trace: {} ({}), {} rays from {}, {} hit, {} in {:.3f} s -> {}\n", scene.name,
               scene.primitivesText(), rays.rays.size(), rays.origin, traced.hitCount, accel->name(), traced.seconds,
               args->hits);
    nlohmann::json report = tracerReport("trace", scene, *accel, rays.rays.size(), traced, buildSeconds);
    report["rays_source"] = rays.origin;
    report["hits_csv"] = args->hits;
    writeReport(args->tracer.report, report);
  });
}

}  // namespace lancer::cli
