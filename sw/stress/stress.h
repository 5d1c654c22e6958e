#pragma once

// `lancer stress` (docs/stability.md): every generated hard case, in every
// placement, through every hardware path and model of this build, checked
// three ways:
//   - bit for bit against the golden model (a mismatch is a model bug);
//   - against the exact truth (the exact arbiter, sw/oracle/exact.h: exact
//     arithmetic on the scene's floats, the limit float64 approaches), each
//     difference classed as a tie, within the lattice's error bound, or beyond
//     it (a bug of the number formats);
//   - against the base placement: bit for bit under a power-of-two scale, and
//     counted (judged by the bound above) under a translation or a stretch.

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stress/variants.h"

namespace lancer::stress {

struct StressOptions {
  std::vector<std::string> cases;   // empty: all
  std::vector<std::string> units;   // hardware paths (--accel names); empty: all
  std::vector<std::string> models;  // empty: every model of each path
  size_t rays = 1000;               // per case
  uint64_t seed = 1;
  std::vector<int> scales{-60, -40, -20, 20, 40, 60};
  std::vector<double> translations{10, 1000};
  std::vector<double> stretches{100, 10000};
};

// One case in one placement on one path and model.
struct StressRow {
  std::string caseName, variant, unit, model;
  uint64_t rays = 0, inLattice = 0, hits = 0;
  uint64_t mismatches = 0;         // vs the golden model, bit for bit
  uint64_t differs = 0;            // hit/miss or triangle differs from the exact truth
  uint64_t hitMissDiffers = 0;     // of those, hit where the truth misses or the reverse
  std::array<uint64_t, 4> verdicts{};  // Verdict: correct, tie, within the bound, beyond it
  uint64_t mustHit = 0;
  // Rays that must hit and missed although the hardware's own ray, in exact
  // arithmetic, meets its own lattice mesh: a leak between its triangles.
  uint64_t cracks = 0;
  // Rays that must hit and missed because the hardware's ray passes outside its
  // lattice mesh (a grazing ray the rounding of the direction turns away).
  uint64_t latticeMisses = 0;
  uint64_t baseDiffers = 0;        // rays whose answer differs from the base placement's (all fields
                                   // of the record for a power-of-two scale; hit/miss or triangle otherwise)
  bool latticeExact = false;
  std::optional<uint32_t> firstBeyond, firstCrack, firstBaseDiffers;
  std::string firstBeyondDetails;  // the judge's reason, the ray (hex floats), both answers
  double hostSeconds = 0;

  // What fails the run: a mismatch, an answer beyond the bound, a crack where
  // the lattice holds the shape, a power-of-two scale that changed an answer.
  bool failed(bool warned) const;
  nlohmann::json toJson() const;
  static StressRow fromJson(const nlohmann::json& j);
};

// One case in one placement: what it is, and how its lattice holds it.
struct PlacementInfo {
  std::string caseName, variant, description;
  uint64_t rays = 0, triangles = 0, latticeRejected = 0;
  LatticeFit fit;
  nlohmann::json toJson() const;
  static PlacementInfo fromJson(const nlohmann::json& j);
};

struct StressResult {
  std::vector<PlacementInfo> placements;
  std::vector<StressRow> rows;
  // Whether the row's placement carries a lattice warning, and whether the row fails.
  bool warned(const StressRow& row) const;
  bool failed(const StressRow& row) const { return row.failed(warned(row)); }
  uint64_t failures() const;
  nlohmann::json toJson() const;
  // The result back from toJson() (another width's report); throws nlohmann's
  // exceptions for a missing key.
  static StressResult fromJson(const nlohmann::json& j);
};

// Progress: called before each case placement is run.
using StressProgress = std::function<void(const PlacementInfo&, size_t index, size_t total)>;

// Throws InputError for an unknown case, unit or model, or a placement beyond float range.
StressResult runStress(const StressOptions& options, const StressProgress& progress = {});

// The tables of docs/stability.md: per case and placement (every unit and
// model folded in), and per case and model (every placement folded in).
std::string placementTable(const StressResult& result);
std::string caseLegend(const StressResult& result);  // a line a case: its name and what it is
std::string modelTable(const StressResult& result);

}  // namespace lancer::stress
