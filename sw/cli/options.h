#pragma once

// Options shared by the subcommands, so every command spells them the same way.

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "driver/job.h"
#include "effects/plan.h"
#include "golden/unit.h"
#include "ref/accel.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace lancer::cli {

struct SceneOptions {
  std::string scene = kDefaultSceneName;
  int subdivide = 0;
  // NFF's spheres and cones: quadrics, unless a command needs triangles (the
  // scene writer, crack rays at shared edges) and sets Tessellate before add().
  QuadricForm quadrics = QuadricForm::Native;
  void add(CLI::App& app);
  // The scene, subdivided --subdivide times (for large benchmark meshes).
  Scene load() const;
};

struct CameraArgs {
  std::vector<float> eye, target, up;
  std::optional<float> fov;
  int width = 512;
  int height = 512;
  void add(CLI::App& app);
  CameraOptions resolve() const;
};

// A unit's build option (golden/unit.h) on a command, setting `into`: its flag
// and rule from the descriptor, the help and largest value of the structure
// the command builds. A value below the rule or above `max` is an InputError
// naming the flag (exit status 1) before anything runs.
void addBuildOption(CLI::App& app, const fx::BuildOption& option, const std::string& help, int max,
                    AccelOptions& into);

// --accel and every traversal unit's build option that shapes the float
// structure (BuildOption::shapesReference), as the float structure takes it.
struct AccelArgs {
  std::string accel = "bvh";
  AccelOptions options;
  void add(CLI::App& app, const std::vector<std::string>& allowed);
};

// What the reference-tracer commands (render, trace) share: the scene, the
// structure (any of the four) and the report. build() builds the structure
// over the loaded scene (which must outlive it), timing the build.
struct TracerArgs {
  SceneOptions scene;
  AccelArgs accel;
  std::string report;
  void add(CLI::App& app);
  std::unique_ptr<Accel> build(const Scene& loaded, double* buildSeconds) const;
};

// The effects of a Whitted run (docs/effects.md): --effects, --max-depth,
// --light-samples, --sampling. `lancer render --whitted` and `lancer run` share them.
struct EffectsArgs {
  std::vector<std::string> effects;
  int maxDepth = 5;
  int lightSamples = 1;
  std::string sampling = "centers";
  // Adds the options; with `needs`, each requires that flag (e.g. --whitted).
  void add(CLI::App& app, CLI::Option* needs = nullptr);
  EffectsOptions options() const { return {effects, maxDepth, lightSamples}; }
  // Throws InputError naming --sampling for an unknown value.
  Sampling parsedSampling() const { return parseSampling(sampling); }
};

// Rays from --rays FILE, or from the camera when no file is given.
struct RaySource {
  std::string raysFile;
  CameraArgs camera;
  void add(CLI::App& app);
  bool fromCamera() const { return raysFile.empty(); }
};

// The chip of N traversal units and its memory system (docs/chip.md): --units,
// --memory fixed|hierarchy, the caches' and DRAM's sizes, the dispatcher and
// the host threads, written into a JobConfig. Values are checked when the
// job starts (checkChipOptions), each message naming its option.
struct ChipArgs {
  std::string memory = "fixed";
  std::string schedule = "fifo";
  void add(CLI::App& app, JobConfig& job);
  // The memory kind and the schedule into `job` (InputError for an unknown --memory or --schedule).
  void apply(JobConfig& job) const;
  // The chip's options as typed, for a replay command (empty for one unit on the fixed memory).
  static std::string replayOptions(const JobConfig& job);
};

// Writes a JSON report if a path was given (throws InputError if it cannot).
void writeReport(const std::string& path, const nlohmann::json& report);

// Builds the structure, timing the build; prints nothing.
std::unique_ptr<Accel> buildAccel(const std::string& kind, const Scene& scene, const AccelOptions& options,
                                  double* seconds = nullptr);

// The reference tracer's answer for a command's rays: the closest hits, the
// traversal counters, the wall-clock seconds of the trace, and how many hit.
struct TracedRays {
  std::vector<std::optional<Hit>> hits;
  TraversalStats stats;
  double seconds = 0;
  size_t hitCount = 0;
};
// Traces `rays` through `accel`, showing progress as `command`.
TracedRays traceTimed(const char* command, const Accel& accel, std::span<const Ray> rays);
// The report fields every reference-tracer command (render, trace) writes;
// the command adds its own.
nlohmann::json tracerReport(const char* command, const Scene& scene, const Accel& accel, size_t rays,
                            const TracedRays& traced, double buildSeconds);

void addRenderCommand(CLI::App& app);
void addTraceCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addRunCommand(CLI::App& app);
void addMergeCommand(CLI::App& app);
void addSpdCommand(CLI::App& app);
void addConvertCommand(CLI::App& app);
void addSweepCommand(CLI::App& app);  // sweep, sweep-job, sweep-merge, crack-rays
void addStressCommand(CLI::App& app);

}  // namespace lancer::cli

namespace lancer::cli {

// The rays a command traces, with the camera when they came from one.
struct Rays {
  std::vector<Ray> rays;
  std::optional<PinholeCamera> camera;
  std::string origin;  // the rays file, or "camera"
};
Rays loadRays(const RaySource& source, const Scene& scene);

}  // namespace lancer::cli
