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

double UnitSilicon::macroAreaMm2() const {
  double a = 0;
  for (const MacroFigures& m : macros) a += m.areaMm2;
  return a;
}

double UnitSilicon::macroLeakageW() const {
  double w = 0;
  for (const MacroFigures& m : macros) w += m.leakageMw * 1e-3;
  return w;
}

double UnitSilicon::macroPjPerCycleBound() const {
  double pj = 0;
  for (const MacroFigures& m : macros) pj += m.readPorts * m.readEnergyPj + m.writePorts * m.writeEnergyPj;
  return pj;
}

nlohmann::json UnitSilicon::toJson() const {
  nlohmann::json macroRows = nlohmann::json::array();
  for (const MacroFigures& m : macros) {
    macroRows.push_back({{"name", m.name}, {"words", m.words}, {"width", m.width}, {"read_ports", m.readPorts},
                         {"write_ports", m.writePorts}, {"area_mm2", m.areaMm2}, {"read_energy_pj", m.readEnergyPj},
                         {"write_energy_pj", m.writeEnergyPj}, {"leakage_mw", m.leakageMw}});
  }
  return {{"library", library},         {"clock_source", clockSource}, {"node_nm", nodeNm},
          {"fmax_mhz", fmaxMhz},        {"critical_path", criticalPath}, {"logic_area_um2", logicAreaUm2},
          {"cells", cells},             {"flip_flops", flipFlops},     {"macros", macroRows},
          {"power_at_mhz", powerAtMhz}, {"dynamic_w", dynamicW},       {"leakage_w", leakageW},
          {"vectorless_w", vectorlessW}, {"workload", workload}};
}

nlohmann::json UnitClock::toJson() const {
  nlohmann::json j = {{"top", top},         {"pos_bits", posBits},     {"dir_bits", dirBits},
                      {"logic_depth", logicDepth}, {"fmax_mhz", fmaxMhz}, {"cells", cells},
                      {"flip_flops", flipFlops},   {"critical_path", criticalPath}, {"commit", commit}};
  if (silicon) j["silicon"] = silicon->toJson();
  return j;
}

namespace {

// A row's "silicon" object (scripts/clock-table --silicon).
UnitSilicon parseSilicon(const nlohmann::json& s) {
  UnitSilicon u;
  u.library = s.at("library").get<std::string>();
  u.clockSource = s.at("clock_source").get<std::string>();
  u.nodeNm = s.at("node_nm").get<int>();
  u.fmaxMhz = s.at("fmax_mhz").get<double>();
  u.criticalPath = s.value("critical_path", nlohmann::json::object());
  u.logicAreaUm2 = s.at("logic_area_um2").get<double>();
  u.cells = s.value("cells", int64_t(0));
  u.flipFlops = s.value("flip_flops", int64_t(0));
  for (const nlohmann::json& m : s.value("macros", nlohmann::json::array())) {
    u.macros.push_back({m.at("name").get<std::string>(), m.at("words").get<int>(), m.at("width").get<int>(),
                        m.at("read_ports").get<int>(), m.at("write_ports").get<int>(), m.at("area_mm2").get<double>(),
                        m.at("read_energy_pj").get<double>(), m.at("write_energy_pj").get<double>(),
                        m.at("leakage_mw").get<double>()});
  }
  u.powerAtMhz = s.value("power_at_mhz", 0.0);
  u.dynamicW = s.value("dynamic_w", 0.0);
  u.leakageW = s.value("leakage_w", 0.0);
  u.vectorlessW = s.value("vectorless_w", 0.0);
  u.workload = s.value("workload", "");
  if (!(u.fmaxMhz > 0)) throw std::invalid_argument("silicon.fmax_mhz must be positive");
  if (!(u.logicAreaUm2 > 0)) throw std::invalid_argument("silicon.logic_area_um2 must be positive");
  return u;
}

}  // namespace

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
      if (r.contains("silicon")) c.silicon = parseSilicon(r["silicon"]);
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

std::vector<std::string> rtlTops(fx::UnitKind path, bool quadrics) {
  std::vector<std::string> tops{"rt_isect"};
  if (quadrics) tops.emplace_back("rt_quadric");
  fx::forEachTraversalUnit([&](auto unit) {
    if (decltype(unit)::kKind == path) tops.emplace_back(decltype(unit)::kNames.module);
  });
  return tops;
}

namespace {

// The slowest row among `tops` that `fits`, by STA's clocks or the gate model's.
template <class Fits>
std::optional<UnitClock> slowest(std::span<const UnitClock> table, const std::vector<std::string>& tops, bool sta,
                                 Fits fits) {
  std::optional<UnitClock> best;
  for (const UnitClock& row : table) {
    if (std::find(tops.begin(), tops.end(), row.top) == tops.end() || !fits(row)) continue;
    if (!best || row.clockMhz(sta) < best->clockMhz(sta)) best = row;
  }
  return best;
}

}  // namespace

RunClock chooseRunClock(std::span<const UnitClock> table, fx::UnitKind path, int posBits, int dirBits,
                        std::optional<double> optionMhz, bool quadrics) {
  const std::vector<std::string> tops = rtlTops(path, quadrics);
  RunClock clock;
  clock.posBits = posBits;
  clock.dirBits = dirBits;
  // An estimate needs every unit of the run at these widths (the slowest may
  // be the one missing); without, the slowest of them at any widths.
  const auto atWidths = [&](const UnitClock& r) { return r.posBits == posBits && r.dirBits == dirBits; };
  const bool complete = std::all_of(tops.begin(), tops.end(), [&](const std::string& top) {
    return std::any_of(table.begin(), table.end(), [&](const UnitClock& r) { return r.top == top && atWidths(r); });
  });
  for (const UnitClock& r : table) {
    if (atWidths(r) && std::find(tops.begin(), tops.end(), r.top) != tops.end()) clock.rows.push_back(r);
  }
  // STA's clocks only when every unit of the run has them: one model for the whole run.
  clock.sta = complete && std::all_of(clock.rows.begin(), clock.rows.end(), [](const UnitClock& r) {
    return r.silicon.has_value();
  });
  if (complete) {
    clock.estimate = slowest(table, tops, clock.sta, atWidths);
  } else {
    clock.source = RunClock::Source::Fallback;
    clock.estimate = slowest(table, tops, false, [](const UnitClock&) { return true; });
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
  clock.mhz = clock.estimate->clockMhz(clock.sta);
  return clock;
}

RunClock runClock(fx::UnitKind path, std::optional<double> optionMhz, bool quadrics) {
  return chooseRunClock(unitClocks(), path, fx::kPosBits, fx::kDirBits, optionMhz, quadrics);
}

std::string RunClock::model() const { return sta && estimate ? estimate->silicon->clockSource : "gate model"; }

std::string RunClock::describe() const {
  const auto depth = [](const UnitClock& r) { return fmt::format("logic depth {} gates", r.logicDepth); };
  switch (source) {
    case Source::Estimate:
      if (sta) {
        return fmt::format("{:g} MHz, the STA clock of the slowest unit, {} ({})", mhz, estimate->where(), model());
      }
      return fmt::format("{:g} MHz, the estimated clock of the slowest unit, {} ({}, gate model)", mhz,
                         estimate->where(), depth(*estimate));
    case Source::Fallback:
      return fmt::format("{:g} MHz: not every unit of this run synthesized at {}/{}; the slowest measured, {} ({})", mhz,
                         posBits, dirBits, estimate->where(), depth(*estimate));
    case Source::Option:
      if (!estimate) return fmt::format("{:g} MHz (--clock-mhz; no estimate to override)", mhz);
      return fmt::format("{:g} MHz (--clock-mhz, overriding the estimate of {:g} MHz for {})", mhz,
                         estimate->clockMhz(sta), estimate->where());
  }
  return {};
}

nlohmann::json RunClock::toJson() const {
  static constexpr const char* kNames[] = {"estimate", "fallback", "option"};
  nlohmann::json j = {{"kind", kNames[int(source)]}, {"mhz", mhz}, {"model", model()}, {"text", describe()}};
  if (estimate) j["estimate"] = estimate->toJson();
  return j;
}

}  // namespace lancer
