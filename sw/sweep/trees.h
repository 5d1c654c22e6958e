#pragma once

// The build trees of a sweep: one per width, configured from the spec's source
// with -DLANCER_POS_BITS / -DLANCER_DIR_BITS, building only the `lancer` target
// (it includes the Verilated models), and reused when up to date. A tree given
// with --tree (e.g. the test suite's build and build-narrow) is used as it is,
// after checking it was configured for its width.

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "sweep/spec.h"

namespace lancer::sweep {

struct TreeResult {
  Width width;
  std::string dir;
  bool ok = false;
  bool upToDate = false;           // the build had nothing to do
  std::optional<double> buildSeconds;  // of the last build of this tree that compiled something
  std::string error;               // names the width; the log holds the details
  std::string log;
  nlohmann::json toJson() const;
};

// Configures (if needed) and builds the tree of `w`; never throws for a failed
// build (ok = false, error set). Logs go to <out>/trees/<tag>.log.
TreeResult buildTree(const Spec& spec, const Width& w, const std::string& out);

// The build seconds recorded in a tree (its build from a fresh configure), if any.
std::optional<double> recordedBuildSeconds(const std::string& tree);

// The `lancer` binary of a tree.
std::string lancerOf(const std::string& tree);

// Yosys synthesis of `top` in the tree of `w` (scripts/sweep-synth), cached in
// the tree at synth/<top>/sweep-synth.json while rt_pkg.sv and the RTL sources are the same.
// Returns the cached or new figures, or an object with "error".
nlohmann::json synthTree(const Spec& spec, const Width& w, const std::string& top, const std::string& out);

}  // namespace lancer::sweep
