// lancer: the command line of the Lancer ray-tracing ASIC simulator.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli/options.h"
#include "common/error.h"

int main(int argc, char** argv) {
  CLI::App app{"Lancer: a cycle-level simulator of a ray-tracing ASIC"};
  app.require_subcommand(1);
  lancer::cli::addRenderCommand(app);
  lancer::cli::addTraceCommand(app);
  lancer::cli::addBenchCommand(app);
  lancer::cli::addRunCommand(app);
  lancer::cli::addMergeCommand(app);
  lancer::cli::addSpdCommand(app);
  lancer::cli::addConvertCommand(app);
  lancer::cli::addSweepCommand(app);
  lancer::cli::addStressCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const lancer::InputError& e) {
    std::fputs(fmt::format("lancer: error: {}\n", e.what()).c_str(), stderr);
    return 1;
  } catch (const lancer::CheckFailed& e) {
    std::fputs(fmt::format("lancer: check failed: {}\n", e.what()).c_str(), stderr);
    return 4;
  } catch (const std::exception& e) {
    std::fputs(fmt::format("lancer: internal error: {}\n", e.what()).c_str(), stderr);
    return 3;
  }
  return 0;
}
