// lancer stress: the stability suite (docs/stability.md). Generated hard cases,
// placed at scales from 2^-60 to 2^60, far from the origin and stretched,
// through every hardware path and model, against the golden model, the exact
// truth and the base placement. Other widths run in their own build trees (as
// lancer sweep builds them), and their results join the one report.
#include <filesystem>
#include <memory>
#include <optional>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli/options.h"
#include "common/error.h"
#include "common/progress.h"
#include "driver/job.h"
#include "golden/formats.h"
#include "stress/stress.h"
#include "sweep/process.h"
#include "sweep/spec.h"
#include "sweep/trees.h"

namespace lancer::cli {

namespace {

struct StressArgs {
  stress::StressOptions options;
  std::vector<std::string> scales, translations, stretches;  // "none" for an empty list
  bool quick = false;
  std::string report;
  std::vector<std::string> widths, trees;
  std::string work = "lancer-stress";
  sweep::Spec spec;  // source, tree pattern, build jobs of the width trees
};

template <class T>
std::vector<T> parseList(const std::vector<std::string>& items, const char* option) {
  std::vector<T> out;
  for (const std::string& item : items) {
    if (item == "none") continue;
    try {
      size_t used = 0;
      const double value = std::stod(item, &used);
      if (used != item.size()) throw std::invalid_argument(item);
      if constexpr (std::is_integral_v<T>) {
        if (value != double(T(value))) throw std::invalid_argument(item);
      }
      out.push_back(T(value));
    } catch (const std::logic_error&) {
      throw InputError(fmt::format("{} {}: not a number", option, item));
    }
  }
  return out;
}

// The options a width's own `lancer stress` repeats.
std::vector<std::string> forwarded(const StressArgs& a, const CLI::App& cmd) {
  std::vector<std::string> argv;
  const auto list = [&](const char* flag, const std::vector<std::string>& values) {
    if (!values.empty()) argv.insert(argv.end(), {flag, fmt::format("{}", fmt::join(values, ","))});
  };
  list("--cases", a.options.cases);
  list("--units", a.options.units);
  list("--models", a.options.models);
  if (a.quick) argv.push_back("--quick");
  for (const char* flag : {"--rays", "--seed"}) {
    if (cmd.count(flag)) argv.insert(argv.end(), {flag, cmd.get_option(flag)->as<std::string>()});
  }
  if (cmd.count("--scales")) list("--scales", a.scales);
  if (cmd.count("--translations")) list("--translations", a.translations);
  if (cmd.count("--stretches")) list("--stretches", a.stretches);
  return argv;
}

void printResult(const nlohmann::json& width, const stress::StressResult& r) {
  fmt::print("\ncases:\n{}", stress::caseLegend(r));
  fmt::print("\nwidth {}/{}: per case and placement (every unit and model; differ %, hit/miss %: the worst of them)\n{}",
             width["pos_bits"].get<int>(), width["dir_bits"].get<int>(), stress::placementTable(r));
  fmt::print("\nwidth {}/{}: per case, unit and model (every placement)\n{}", width["pos_bits"].get<int>(),
             width["dir_bits"].get<int>(), stress::modelTable(r));
  for (const stress::PlacementInfo& p : r.placements) {
    if (!p.fit.warning.empty()) fmt::print("  warning: {}, {}: {}\n", p.caseName, p.variant, p.fit.warning);
  }
  for (const stress::StressRow& row : r.rows) {
    if (!r.failed(row)) continue;
    fmt::print("  FAILED {}, {}, {} {}: {} mismatches, {} beyond the bound (first ray {}), {} cracks (first {}), {} "
               "differ from the base placement (first {})\n",
               row.caseName, row.variant, row.unit, row.model, row.mismatches, row.verdicts[3],
               row.firstBeyond ? fmt::format("{}", *row.firstBeyond) : "-", row.cracks,
               row.firstCrack ? fmt::format("{}", *row.firstCrack) : "-", row.baseDiffers,
               row.firstBaseDiffers ? fmt::format("{}", *row.firstBaseDiffers) : "-");
    if (row.firstBeyond) fmt::print("         ray {}: {}\n", *row.firstBeyond, row.firstBeyondDetails);
  }
}

// Runs `lancer stress` of another width's tree; returns its result JSON.
nlohmann::json runOtherWidth(const StressArgs& a, const CLI::App& cmd, const sweep::Width& w) {
  const sweep::TreeResult tree = sweep::buildTree(a.spec, w, a.work);
  if (!tree.ok) throw InputError(tree.error);
  const std::string report = fmt::format("{}/stress-{}.json", a.work, w.tag());
  const std::string log = fmt::format("{}/stress-{}.log", a.work, w.tag());
  std::filesystem::remove(report);
  std::vector<std::string> argv{sweep::lancerOf(tree.dir), "stress"};
  const std::vector<std::string> more = forwarded(a, cmd);
  argv.insert(argv.end(), more.begin(), more.end());
  argv.insert(argv.end(), {"--report", report});
  fmt::print("width {}: {} (log {})\n", w.name(), sweep::shellJoin(argv), log);
  std::fflush(stdout);
  const int status = sweep::runLogged(argv, log);
  const nlohmann::json j = sweep::readJson(report);
  // Status 4: the run completed and its checks failed; its report holds why.
  if ((status != 0 && status != 4) || !j.is_object()) {
    throw InputError(fmt::format("width {}: lancer stress in {} failed (exit {}): {}", w.name(), tree.dir, status,
                                 sweep::errorLine(log)));
  }
  if (!j.contains("widths") || !j["widths"].is_array() || j["widths"].size() != 1 ||
      !j["widths"][0].contains("placements")) {
    throw InputError(fmt::format("width {}: {} is not a one-width stress report (is {} older than this lancer?)",
                                 w.name(), report, tree.dir));
  }
  return j["widths"][0];
}

void runStressCommand(StressArgs a, const CLI::App& cmd) {
  if (a.quick) {
    if (!cmd.count("--rays")) a.options.rays = 150;
    if (!cmd.count("--scales")) a.scales = {"-60", "60"};
    if (!cmd.count("--translations")) a.translations = {"1000"};
    if (!cmd.count("--stretches")) a.stretches = {"10000"};
  }
  if (cmd.count("--scales") || a.quick) a.options.scales = parseList<int>(a.scales, "--scales");
  if (cmd.count("--translations") || a.quick) a.options.translations = parseList<double>(a.translations, "--translations");
  if (cmd.count("--stretches") || a.quick) a.options.stretches = parseList<double>(a.stretches, "--stretches");
  if (a.options.rays == 0) throw InputError("--rays 0: a case needs rays");
  // Every list checked before anything runs, in this width and the others.
  stress::makeVariants(a.options.scales, a.options.translations, a.options.stretches);
  for (const std::string& c : a.options.cases) stress::makeCase(c, 8, a.options.seed);

  const sweep::Width own{fx::kPosBits, fx::kDirBits};
  std::vector<sweep::Width> widths;
  for (const std::string& w : a.widths) widths.push_back(sweep::parseWidth(w, "--widths"));
  if (widths.empty()) widths.push_back(own);
  for (const std::string& t : a.trees) a.spec.addTree(t);
  a.spec.resolvePaths();
  if (widths.size() > 1 || widths[0] != own) std::filesystem::create_directories(a.work);

  nlohmann::json perWidth = nlohmann::json::array();
  uint64_t failures = 0;
  for (const sweep::Width& w : widths) {
    nlohmann::json j;
    if (w == own) {
      std::optional<Progress> progress;
      const stress::StressResult r = stress::runStress(a.options, [&](const stress::PlacementInfo&, size_t, size_t total) {
        if (!progress) progress.emplace(fmt::format("stress {}", w.name()), total);
        progress->advance();
      });
      if (progress) progress->finish();
      j = r.toJson();
    } else {
      j = runOtherWidth(a, cmd, w);
    }
    failures += j.at("failures").get<uint64_t>();
    printResult(j, stress::StressResult::fromJson(j));
    perWidth.push_back(j);
  }
  nlohmann::json report = {{"command", "stress"}, {"rays_per_case", a.options.rays}, {"seed", a.options.seed},
                           {"widths", perWidth},  {"failures", failures}};
  writeReport(a.report, report);
  fmt::print("\nstress: {} widths, {} failed rows\n", widths.size(), failures);
  if (failures) throw CheckFailed(fmt::format("{} stress rows failed (listed above)", failures));
}

}  // namespace

void addStressCommand(CLI::App& app) {
  auto a = std::make_shared<StressArgs>();
  CLI::App* cmd = app.add_subcommand("stress", "The stability suite: generated hard cases at every scale and "
                                               "placement, through every model (docs/stability.md)");
  cmd->add_option("--cases", a->options.cases,
                  fmt::format("Cases (default all: {})", fmt::join(stress::caseNames(), ", ")))
      ->delimiter(',');
  cmd->add_option("--units", a->options.units,
                  fmt::format("Hardware paths: {} (default all)", fmt::join(hardwarePathNames(), ", ")))
      ->delimiter(',');
  cmd->add_option("--models", a->options.models, "Models (default every model of each path)")->delimiter(',');
  cmd->add_option("--rays", a->options.rays, "Rays per case")->capture_default_str();
  cmd->add_option("--seed", a->options.seed, "Seed of the generated scenes and rays")->capture_default_str();
  cmd->add_option("--scales", a->scales, "Power-of-two scales, as exponents (default -60,-40,-20,20,40,60; none)")
      ->delimiter(',');
  cmd->add_option("--translations", a->translations,
                  "Translations, in scene sizes from the origin (default 10,1000; none)")
      ->delimiter(',');
  cmd->add_option("--stretches", a->stretches, "Stretch factors along x (default 100,10000; none)")->delimiter(',');
  cmd->add_flag("--quick", a->quick,
                "The short form of the test suite: 150 rays a case, scales 2^-60 and 2^60, translation 1000x, stretch "
                "10000:1 (options given still win)");
  cmd->add_option("--report", a->report, "JSON report file");
  cmd->add_option("--widths", a->widths, "Widths P/D to run, each in its own tree (default: this build's)")
      ->delimiter(',');
  cmd->add_option("--tree", a->trees, "Use an existing tree for a width: WIDTH=DIR (repeatable)");
  cmd->add_option("--source", a->spec.source, "Lancer source tree to configure width trees from")
      ->default_str(LANCER_SOURCE_DIR);
  cmd->add_option("--tree-pattern", a->spec.treePattern,
                  "Where a width's tree goes: {pos} and {dir} replaced (default <source>/build-sweep/{pos}-{dir})");
  cmd->add_option("--build-jobs", a->spec.buildJobs, "Parallel compile jobs per tree build")->capture_default_str();
  cmd->add_option("--work", a->work, "Folder for other widths' logs and reports")->capture_default_str();
  cmd->callback([a, cmd] { runStressCommand(*a, *cmd); });
}

}  // namespace lancer::cli
