// lancer merge: the shards of an ao or path run (lancer run --shard I/N) into
// the whole frame's report and images (cli/shards.h).
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli/options.h"
#include "cli/shards.h"
#include "common/pfm.h"
#include "common/png.h"
#include "driver/report.h"
#include "effects/whitted.h"
#include "scene/camera.h"

namespace lancer::cli {

namespace {

struct MergeArgs {
  std::vector<std::string> shards;
  std::string image, refImage, pfm, report;
};

void merge(const MergeArgs& args) {
  const MergedFrame frame = mergeShards(args.shards);
  const nlohmann::json& r = frame.report;
  const int width = r["width"], height = r["height"];
  const Sampling sampling = parseSampling(r["sampling"].get<std::string>());
  fmt::print("merge: {} shards of {} on {} {} ({}x{}, {} samples): {} mismatches, {} beyond the bound, image rel. MSE "
             "vs float reference {:.3g}\n",
             r["shards"].get<int>(), r["scene"].get<std::string>(), r["accel"].get<std::string>(),
             r["model"].get<std::string>(), width, height, frame.hardware.size(), r["mismatches"].get<uint64_t>(),
             r["beyond_bound"].get<uint64_t>(), r["image_rel_mse"].get<double>());
  for (const auto& [name, c] : r["classes"].items()) {
    fmt::print("  {:<11} {:>10} rays {:>10} hits\n", name, c.value("rays", uint64_t(0)), c.value("hits", uint64_t(0)));
  }
  if (!args.image.empty()) writePng(samplesToImage(frame.hardware, width, height, sampling), args.image);
  if (!args.refImage.empty()) writePng(samplesToImage(frame.reference, width, height, sampling), args.refImage);
  if (!args.pfm.empty()) writePfm(samplesToPixels(frame.hardware, width, height, sampling), width, height, args.pfm);
  writeReport(args.report, r);
  if (r["mismatches"].get<uint64_t>() != 0) throw CheckFailed(fmt::format("{} mismatched rays", r["mismatches"].dump()));
}

}  // namespace

void addMergeCommand(CLI::App& app) {
  auto args = std::make_shared<MergeArgs>();
  CLI::App* cmd = app.add_subcommand("merge", "Join the shards of an ao or path run (run --shard I/N) into its frame");
  cmd->add_option("shards", args->shards, "The shards' reports (each with its .samples beside it)")->required();
  cmd->add_option("--image", args->image, "PNG of the frame from the model's hits");
  cmd->add_option("--ref-image", args->refImage, "PNG of the frame on the float reference");
  cmd->add_option("--pfm", args->pfm, "The frame's linear image (PFM)");
  cmd->add_option("--report", args->report, "JSON report of the frame");
  cmd->callback([args] { merge(*args); });
}

}  // namespace lancer::cli
