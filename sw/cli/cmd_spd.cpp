// lancer spd NAME: writes one of the Standard Procedural Databases as NFF on
// stdout (Lancer's own generator, sw/scene/spd.h), e.g. `lancer spd tetra > tetra.nff`.
#include <cstdio>

#include <fmt/format.h>

#include "cli/options.h"
#include "scene/spd.h"

namespace lancer::cli {

void addSpdCommand(CLI::App& app) {
  struct Args {
    std::string name;
    int sizeFactor = 0;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand("spd", "Write an SPD scene (tetra, gears) as NFF on stdout; also builtin:spd-NAME[@SIZE]");
  cmd->add_option("name", args->name, "Scene: tetra or gears")->required();
  cmd->add_option("--size-factor", args->sizeFactor, "The SPD's size factor (default: the SPD's, tetra 6, gears 4; tetra 1..10, gears 1..16)");
  cmd->callback([args] { std::fputs(generateSpdNff(args->name, args->sizeFactor).c_str(), stdout); });
}

}  // namespace lancer::cli
