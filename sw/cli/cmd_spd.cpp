// lancer spd NAME: writes one of the Standard Procedural Databases as NFF on
// stdout (Lancer's own generator, sw/scene/spd.h), e.g. `lancer spd tetra > tetra.nff`.
#include <cstdio>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli/options.h"
#include "scene/spd.h"

namespace lancer::cli {

void addSpdCommand(CLI::App& app) {
  struct Args {
    std::string name;
    int sizeFactor = 0;
  };
  auto args = std::make_shared<Args>();
  const std::string names = fmt::format("{}", fmt::join(spdSceneNames(), ", "));
  CLI::App* cmd = app.add_subcommand(
      "spd", fmt::format("Write an SPD scene ({}) as NFF on stdout; also builtin:spd-NAME[@SIZE]", names));
  cmd->add_option("name", args->name, "Scene: " + names)->required();
  cmd->add_option("--size-factor", args->sizeFactor,
                  "The SPD's size factor (default: the SPD's; ranges: tetra 1..10, gears 1..16, balls 1..5, "
                  "mount 1..7, rings 1..20, tree 1..16)");
  cmd->callback([args] { std::fputs(generateSpdNff(args->name, args->sizeFactor).c_str(), stdout); });
}

}  // namespace lancer::cli
