#include "sweep/spec.h"

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <optional>
#include <type_traits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "common/json_keys.h"
#include "golden/quadric.h"
#include "golden/units.h"

namespace lancer::sweep {

namespace {

int parseBits(const std::string& text, const std::string& all, const std::string& where) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) {
    throw InputError(fmt::format("{}: width '{}' is not P/D with integer bits", where, all));
  }
  if (value < 4 || value > 24) {
    throw InputError(fmt::format("{}: width {}: {} bits lies outside what the formats admit (4..24)", where, all,
                                 value));
  }
  return value;
}

// The quadric record's K >= 8 bits (sw/golden/quadric.h), as cmake/NumberFormats.cmake checks.
Width checkQuadricBits(const Width& w, const std::string& all, const std::string& where) {
  if (const int k = fx::quadricCoefficientBits(w.pos, w.dir); k < fx::kQuadricMinK) {
    throw InputError(fmt::format("{}: width {}: the quadric pipeline needs P >= 5 and P + D >= 12 (K = {} bits, at least {})",
                                 where, all, k, fx::kQuadricMinK));
  }
  return w;
}

std::string replaceAll(std::string s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
  return s;
}

}  // namespace

// A spec file's keys, each with the member it sets, once (common/json_keys.h):
// Spec::fromJson, Spec::toJson and fromJson's list of the known keys (in this
// order) all read this table.
static void forEachKey(json_keys::Of<Spec> auto& s, auto&& fn) {
  fn("widths", s.widths), fn("scenes", s.scenes), fn("units", s.units), fn("models", s.models);
  fn("image", s.image), fn("chunks", s.chunks), fn("crack_rays", s.crackRays), fn("seed", s.seed);
  fn("grid_res", s.gridRes), fn("mem_latency", s.memLatency), fn("clock_mhz", s.clockMhz), fn("synth", s.synth);
  fn("synth_units", s.synthUnits), fn("source", s.source), fn("tree_pattern", s.treePattern);
  fn("trees", s.trees), fn("cmake_args", s.cmakeArgs), fn("build_jobs", s.buildJobs);
}

// A plan's job record, likewise (Job::toJson, Job::fromJson).
static void forEachKey(json_keys::Of<Job> auto& job, auto&& fn) {
  fn("key", job.key), fn("width", job.width), fn("unit", job.unit), fn("model", job.model);
  fn("scene", job.scene), fn("set", job.set), fn("chunk", job.chunk);
}

std::string Width::name() const { return fmt::format("{}/{}", pos, dir); }
std::string Width::tag() const { return fmt::format("{}-{}", pos, dir); }

Width parseWidth(const std::string& text, const std::string& where) {
  const size_t slash = text.find('/');
  if (slash == std::string::npos) {
    const int bits = parseBits(text, text, where);
    return checkQuadricBits({bits, bits}, text, where);
  }
  return checkQuadricBits({parseBits(text.substr(0, slash), text, where), parseBits(text.substr(slash + 1), text, where)},
                          text, where);
}

const std::vector<std::string>& sweepUnits() {
  static const std::vector<std::string> units = [] {
    std::vector<std::string> names{"isect", "quadric"};
    fx::forEachTraversalUnit([&](auto unit) { names.emplace_back(decltype(unit)::kNames.unit); });
    return names;
  }();
  return units;
}

std::string synthTopOf(const std::string& unit) { return "rt_" + unit; }

std::vector<std::string> quadricFormArgs(const std::string& unit) {
  return {"--quadrics", unit == "quadric" ? "native" : "tessellate"};
}

std::vector<std::string> runUnitArgs(const std::string& unit) {
  std::vector<std::string> args{"--accel", unit == "quadric" ? "isect" : unit};
  const std::vector<std::string> form = quadricFormArgs(unit);
  args.insert(args.end(), form.begin(), form.end());
  return args;
}

bool isTraversalUnit(const std::string& unit) { return unit != "isect" && unit != "quadric"; }

bool takesCrackRays(const std::string& unit) { return unit != "quadric"; }

void Spec::validate() const {
  if (widths.empty()) throw InputError("--widths: no width to sweep");
  if (scenes.empty()) throw InputError("--scenes: no scene to sweep");
  for (const std::string& u : units) {
    if (std::find(sweepUnits().begin(), sweepUnits().end(), u) == sweepUnits().end()) {
      throw InputError(fmt::format("--units: unknown unit '{}' (available: {})", u, fmt::join(sweepUnits(), ", ")));
    }
  }
  if (units.empty()) throw InputError("--units: no unit to sweep");
  for (const std::string& u : synthUnits) {
    if (std::find(units.begin(), units.end(), u) == units.end()) {
      throw InputError(fmt::format("--synth-units: '{}' is not one of the sweep's units", u));
    }
  }
  for (const std::string& m : models) {
    if (m != "golden" && m != "systemc" && m != "rtl" && m != "rtl-systemc") {
      throw InputError(fmt::format("--models: unknown model '{}' (golden, systemc, rtl, rtl-systemc)", m));
    }
  }
  if (models.empty()) throw InputError("--models: no model to run");
  if (image < 1) throw InputError(fmt::format("--image {}: must be at least 1", image));
  if (chunks < 1 || chunks > image * image) {
    throw InputError(fmt::format("--chunks {}: must lie in 1..{} (the camera rays)", chunks, image * image));
  }
  if (crackRays < 0) throw InputError(fmt::format("--crack-rays {}: must not be negative", crackRays));
  if (clockMhz && !(*clockMhz > 0)) throw InputError(fmt::format("--clock-mhz {}: must be positive", *clockMhz));
  if (buildJobs < 1) throw InputError(fmt::format("--build-jobs {}: must be at least 1", buildJobs));
  std::vector<Width> sorted = widths;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
    throw InputError("--widths: a width is listed twice");
  }
  for (const auto& [name, dir] : trees) {
    const Width w = parseWidth(name, "--tree");
    if (std::find(widths.begin(), widths.end(), w) == widths.end()) {
      throw InputError(fmt::format("--tree {}={}: width {} is not in --widths", name, dir, name));
    }
  }
}

void Spec::addTree(const std::string& widthEqualsDir) {
  const size_t eq = widthEqualsDir.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == widthEqualsDir.size()) {
    throw InputError(fmt::format("--tree {}: expected WIDTH=DIR, e.g. 10/10=build-narrow", widthEqualsDir));
  }
  trees[parseWidth(widthEqualsDir.substr(0, eq), "--tree").name()] = widthEqualsDir.substr(eq + 1);
}

void Spec::resolvePaths() {
  if (source.empty()) source = LANCER_SOURCE_DIR;
  source = std::filesystem::absolute(source).lexically_normal().string();
  if (treePattern.empty()) treePattern = source + "/build-sweep/{pos}-{dir}";
}

std::string Spec::treeOf(const Width& w) const {
  for (const auto& [name, dir] : trees) {
    if (parseWidth(name, "--tree") == w) return dir;
  }
  return replaceAll(replaceAll(treePattern, "{pos}", std::to_string(w.pos)), "{dir}", std::to_string(w.dir));
}

nlohmann::json Spec::toJson() const {
  const auto widthNames = [](const std::vector<Width>& widths) {
    std::vector<std::string> names;
    for (const Width& w : widths) names.push_back(w.name());
    return nlohmann::json(names);
  };
  const auto clock = [](const std::optional<double>& mhz) { return mhz ? nlohmann::json(*mhz) : nlohmann::json(); };
  return json_keys::write(*this, json_keys::Overloaded{widthNames, clock, json_keys::Plain{}});
}

Spec Spec::fromJson(const nlohmann::json& j, const std::string& where) {
  Spec s;
  if (!j.is_object()) throw InputError(fmt::format("{}: a sweep spec is a JSON object", where));
  static const std::vector<std::string> known = [] {
    std::vector<std::string> keys;
    Spec unused;
    forEachKey(unused, [&](const char* key, const auto&) { keys.emplace_back(key); });
    return keys;
  }();
  for (const auto& [key, value] : j.items()) {
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      throw InputError(fmt::format("{}: unknown key '{}' (known: {})", where, key, fmt::join(known, ", ")));
    }
  }
  try {
    const auto widths = [&](const nlohmann::json& spec, const char* key, std::vector<Width>& out) {
      for (const std::string& w : spec.value(key, std::vector<std::string>{})) out.push_back(parseWidth(w, where));
    };
    const auto clock = [](const nlohmann::json& spec, const char* key, std::optional<double>& mhz) {
      if (spec.contains(key) && !spec[key].is_null()) mhz = spec[key].get<double>();
    };
    // Any other key may be left out: its member keeps its default.
    const auto orDefault = [](const nlohmann::json& spec, const char* key, auto& member) {
      member = spec.value(key, member);
    };
    json_keys::read(j, s, json_keys::Overloaded{widths, clock, orDefault});
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: {}", where, e.what()));
  }
  return s;
}

nlohmann::json Job::toJson() const {
  return json_keys::write(
      *this, json_keys::Overloaded{[](const Width& w) { return nlohmann::json(w.name()); }, json_keys::Plain{}});
}

Job Job::fromJson(const nlohmann::json& j) {
  const auto width = [](const nlohmann::json& plan, const char* key, Width& w) {
    w = parseWidth(plan.at(key).get<std::string>(), "plan");
  };
  Job job;
  json_keys::read(j, job, json_keys::Overloaded{width, json_keys::Plain{}});
  return job;
}

std::string Job::describe(const Spec& spec) const {
  const std::string rays = set == "cracks" ? "crack rays" : fmt::format("camera chunk {} of {}", chunk + 1, spec.chunks);
  return fmt::format("job {} (width {}, unit {}, model {}, scene {}, {})", key, width.name(), unit, model,
                     spec.scenes[size_t(scene)], rays);
}

std::string sceneTag(const Spec& spec, int i) {
  std::string stem = std::filesystem::path(spec.scenes[size_t(i)]).stem().string();
  const size_t colon = stem.find(':');
  if (colon != std::string::npos) stem = stem.substr(colon + 1);
  for (char& c : stem) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  }
  return fmt::format("s{}-{}", i, stem);
}

std::vector<Job> makePlan(const Spec& spec) {
  std::vector<Job> jobs;
  for (const Width& w : spec.widths) {
    for (const std::string& unit : spec.units) {
      for (const std::string& model : spec.models) {
        for (int s = 0; s < int(spec.scenes.size()); ++s) {
          const std::string base = fmt::format("w{}.{}.{}.s{}", w.tag(), unit, model, s);
          for (int c = 0; c < spec.chunks; ++c) {
            jobs.push_back({fmt::format("{}.c{}of{}", base, c, spec.chunks), w, unit, model, s, "camera", c});
          }
          if (spec.crackRays > 0 && takesCrackRays(unit)) jobs.push_back({base + ".cracks", w, unit, model, s, "cracks", 0});
        }
      }
    }
  }
  return jobs;
}

}  // namespace lancer::sweep
