#include "driver/clocks.h"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "common/error.h"
#include "golden/formats.h"
#include "golden/units.h"

namespace lancer {

namespace detail {
// rtl/synth/clocks.json as the build found it (generated clocks_table.cpp).
extern const char kClocksJson[];
}  // namespace detail

std::string UnitClock::where() const { return fmt::format("{} at {}/{}", top, posBits, dirBits); }

nlohmann::json UnitClock::toJson() const {
  return {{"top", top},         {"pos_bits", posBits},     {"dir_bits", dirBits},
          {"logic_depth", logicDepth}, {"fmax_mhz", fmaxMhz}, {"cells", cells},
          {"flip_flops", flipFlops},   {"critical_path", criticalPath}, {"commit", commit}};
}

std::vector<UnitClock> parseUnitClocks(const std::string& text, const std::string& where) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || !j.contains("units") || !j["units"].is_array()) {
    throw InputError(fmt::format("{}: not a clock table (a JSON object with a 'units' list)", where));
  }
  std::vector<UnitClock> rows;
  for (const nlohmann::json& r : j["units"]) {
    try {
      UnitClock c;
      c.top = r.at("top").get<std::string>();
      c.posBits = r.at("pos_bits").get<int>();
      c.dirBits = r.at("dir_bits").get<int>();
      c.logicDepth = r.at("logic_depth").get<int>();
      c.fmaxMhz = r.at("fmax_mhz").get<double>();
      c.cells = r.value("cells", int64_t(0));
      c.flipFlops = r.value("flip_flops", int64_t(0));
      c.criticalPath = r.value("critical_path", nlohmann::json::array());
      c.commit = r.value("commit", "");
      if (!(c.fmaxMhz > 0)) throw std::invalid_argument("fmax_mhz must be positive");
      rows.push_back(std::move(c));
    } catch (const std::exception& e) {
      throw InputError(fmt::format("{}: row {} of 'units': {}", where, rows.size(), e.what()));
    }
  }
  return rows;
}

std::span<const UnitClock> unitClocks() {
  static const std::vector<UnitClock> rows = [] {
    try {
      return parseUnitClocks(detail::kClocksJson, "rtl/synth/clocks.json (as built)");
    } catch (const InputError& e) {
      throw std::runtime_error(e.what());
    }
  }();
  return rows;
}

std::vector<std::string> rtlTops(fx::UnitKind path) {
  std::vector<std::string> tops{"rt_isect"};
  fx::forEachTraversalUnit([&](auto unit) {
    if (decltype(unit)::kKind == path) tops.emplace_back(decltype(unit)::kNames.module);
  });
  return tops;
}

namespace {

// The slowest row among `tops` that `fits`.
template <class Fits>
std::optional<UnitClock> slowest(std::span<const UnitClock> table, const std::vector<std::string>& tops, Fits fits) {
  std::optional<UnitClock> best;
  for (const UnitClock& row : table) {
    if (std::find(tops.begin(), tops.end(), row.top) == tops.end() || !fits(row)) continue;
    if (!best || row.fmaxMhz < best->fmaxMhz) best = row;
  }
  return best;
}

}  // namespace

RunClock chooseRunClock(std::span<const UnitClock> table, fx::UnitKind path, int posBits, int dirBits,
                        std::optional<double> optionMhz) {
  const std::vector<std::string> tops = rtlTops(path);
  RunClock clock;
  clock.posBits = posBits;
  clock.dirBits = dirBits;
  // An estimate needs every unit of the run at these widths (the slowest may
  // be the one missing); without, the slowest of them at any widths.
  const auto atWidths = [&](const UnitClock& r) { return r.posBits == posBits && r.dirBits == dirBits; };
  const bool complete = std::all_of(tops.begin(), tops.end(), [&](const std::string& top) {
    return std::any_of(table.begin(), table.end(), [&](const UnitClock& r) { return r.top == top && atWidths(r); });
  });
  if (complete) {
    clock.estimate = slowest(table, tops, atWidths);
  } else {
    clock.source = RunClock::Source::Fallback;
    clock.estimate = slowest(table, tops, [](const UnitClock&) { return true; });
  }
  if (optionMhz) {
    if (!(*optionMhz > 0.0)) throw InputError(fmt::format("--clock-mhz {} must be positive", *optionMhz));
    clock.mhz = *optionMhz;
    clock.source = RunClock::Source::Option;
    return clock;
  }
  if (!clock.estimate) {
    throw InputError(fmt::format("no estimated clock of {} in the clock table (rtl/synth/clocks.json, "
                                 "scripts/clock-table): give --clock-mhz",
                                 fmt::join(tops, " or ")));
  }
  clock.mhz = clock.estimate->fmaxMhz;
  return clock;
}

RunClock runClock(fx::UnitKind path, std::optional<double> optionMhz) {
  return chooseRunClock(unitClocks(), path, fx::kPosBits, fx::kDirBits, optionMhz);
}

std::string RunClock::describe() const {
  const auto depth = [](const UnitClock& r) { return fmt::format("logic depth {} gates", r.logicDepth); };
  switch (source) {
    case Source::Estimate:
      return fmt::format("{:g} MHz, the estimated clock of the slowest unit, {} ({})", mhz, estimate->where(),
                         depth(*estimate));
    case Source::Fallback:
      return fmt::format("{:g} MHz: not every unit of this run synthesized at {}/{}; the slowest measured, {} ({})", mhz,
                         posBits, dirBits, estimate->where(), depth(*estimate));
    case Source::Option:
      if (!estimate) return fmt::format("{:g} MHz (--clock-mhz; no estimate to override)", mhz);
      return fmt::format("{:g} MHz (--clock-mhz, overriding the estimate of {:g} MHz for {})", mhz,
                         estimate->fmaxMhz, estimate->where());
  }
  return {};
}

nlohmann::json RunClock::toJson() const {
  static constexpr const char* kNames[] = {"estimate", "fallback", "option"};
  nlohmann::json j = {{"kind", kNames[int(source)]}, {"mhz", mhz}, {"text", describe()}};
  if (estimate) j["estimate"] = estimate->toJson();
  return j;
}

}  // namespace lancer
