#pragma once

// What a sweep measures (the spec) and the jobs it breaks into (the plan).
// A spec comes from the command line or a JSON file (docs/accuracy.md, "Spec
// file"); the plan is written to <out>/plan.json, and every executor (local
// threads, Slurm array tasks) runs jobs from that file, so they run the same
// commands and write the same results.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace lancer::sweep {

struct Width {
  int pos = 16;
  int dir = 16;
  std::string name() const;  // "16/16"
  std::string tag() const;   // "16-16", for paths
  auto operator<=>(const Width&) const = default;
};

// "P/D" (or "P" for P/P); throws InputError naming `where` unless both lie in
// 4..24 and hold the quadric record (P >= 5, P + D >= 12).
Width parseWidth(const std::string& text, const std::string& where);

// The units a sweep can measure and the Yosys top of each: isect (rt_isect fed
// by the host's BVH), quadric (rt_quadric beside it on the scene's native
// spheres and cones) and every traversal unit.
const std::vector<std::string>& sweepUnits();
std::string synthTopOf(const std::string& unit);
// What selects the unit in `lancer run`: --accel, and how the unit reads NFF's
// spheres and cones (--quadrics): natively for quadric, as triangles for the
// others (their rows measure triangles: rt_isect's accuracy and the units'
// synthesis without rt_quadric). The same form goes to crack-rays and trace.
std::vector<std::string> runUnitArgs(const std::string& unit);
std::vector<std::string> quadricFormArgs(const std::string& unit);
// A traversal unit walks a structure (it takes steps and has a float walk to compare with).
bool isTraversalUnit(const std::string& unit);
// Crack rays aim at shared triangle edges, which the quadric pipeline never tests.
bool takesCrackRays(const std::string& unit);

struct Spec {
  std::vector<Width> widths;
  std::vector<std::string> scenes;
  std::vector<std::string> units{"isect"};
  std::vector<std::string> models{"golden", "rtl"};
  int image = 128;          // camera rays: image x image, auto-framed
  int chunks = 1;           // camera rays split into this many jobs per scene
  int crackRays = 1024;     // per width and scene (0: none)
  uint64_t seed = 1;
  int gridRes = 0;          // 0: the unit's heuristic
  int memLatency = 20;
  std::optional<double> clockMhz;  // the run reports' clock; none: each run's estimate (rtl/synth/clocks.json)
  bool synth = false;
  std::vector<std::string> synthUnits;  // the units synthesized (empty: every unit of the sweep)
  std::string source;       // the Lancer source tree the width trees are configured from
  std::string treePattern;  // a tree's path, {pos} and {dir} replaced
  std::map<std::string, std::string> trees;  // width name -> an existing tree to use
  std::vector<std::string> cmakeArgs;        // extra configure arguments of new trees
  int buildJobs = 2;

  // Throws InputError naming the option for an empty or invalid field.
  void validate() const;
  std::string treeOf(const Width& w) const;
  // The units --synth maps: synthUnits, or every unit of the sweep.
  const std::vector<std::string>& synthesizedUnits() const { return synthUnits.empty() ? units : synthUnits; }
  // --tree WIDTH=DIR; throws InputError naming it when it is not that.
  void addTree(const std::string& widthEqualsDir);
  // The source tree made absolute (this build's source when empty), and the
  // tree pattern <source>/build-sweep/{pos}-{dir} when none was given.
  void resolvePaths();
  nlohmann::json toJson() const;
  static Spec fromJson(const nlohmann::json& j, const std::string& where);
};

// One job: one width, unit, model and scene, on one ray set (a chunk of the
// camera rays, or the width's crack rays).
struct Job {
  std::string key;  // unique, a file name: w10-10.isect.golden.s0.c0of2
  Width width;
  std::string unit, model;
  int scene = 0;    // index into spec.scenes
  std::string set;  // "camera" or "cracks"
  int chunk = 0;
  nlohmann::json toJson() const;
  static Job fromJson(const nlohmann::json& j);
  std::string describe(const Spec& spec) const;  // for messages: width, unit, model, scene, rays
};

std::vector<Job> makePlan(const Spec& spec);

// The short name of scene i (its file's stem), unique within the spec.
std::string sceneTag(const Spec& spec, int i);

}  // namespace lancer::sweep
