#include "cli/shards.h"

#include <charconv>
#include <cstdio>
#include <fstream>
#include <memory>

#include <fmt/format.h>

#include "common/error.h"
#include "effects/integrator.h"

namespace lancer::cli {

Shard parseShard(const std::string& text) {
  Shard s;
  const size_t slash = text.find('/');
  const auto number = [&](std::string_view part, int& out) {
    const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), out);
    return ec == std::errc() && end == part.data() + part.size();
  };
  if (slash == std::string::npos || !number(std::string_view(text).substr(0, slash), s.index) ||
      !number(std::string_view(text).substr(slash + 1), s.count)) {
    throw InputError(fmt::format("--shard {}: expected I/N, shard I of N", text));
  }
  if (s.count < 1 || s.index < 0 || s.index >= s.count) {
    throw InputError(fmt::format("--shard {}: the shard must lie in 0..N-1 of N >= 1", text));
  }
  return s;
}

std::pair<size_t, size_t> shardRange(const Shard& shard, size_t samples) {
  const auto at = [&](int i) { return size_t(uint64_t(samples) * uint64_t(i) / uint64_t(shard.count)); };
  return {at(shard.index), at(shard.index + 1)};
}

std::string samplesFileOf(const std::string& report) { return report + ".samples"; }

void writeShardSamples(const std::string& path, std::span<const glm::vec3> hardware,
                       std::span<const glm::vec3> reference) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw InputError(fmt::format("{}: cannot write the shard's samples", path));
  for (const auto samples : {hardware, reference}) {
    if (std::fwrite(samples.data(), sizeof(glm::vec3), samples.size(), f.get()) != samples.size()) {
      throw InputError(fmt::format("{}: cannot write the shard's samples", path));
    }
  }
}

namespace {

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "samples are written as packed float triples");

nlohmann::json readReport(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(fmt::format("{}: cannot open", path));
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not a JSON report ({})", path, e.what()));
  }
}

// The counters of a class or a run that add up over shards (integers only:
// the sums are exact).
void addCounters(nlohmann::json& into, const nlohmann::json& more) {
  if (!into.is_object()) into = nlohmann::json::object();
  for (const auto& [key, value] : more.items()) {
    if (value.is_number_unsigned() || value.is_number_integer()) {
      into[key] = into.value(key, uint64_t(0)) + value.get<uint64_t>();
    } else if (value.is_object() && key != "chip") {
      addCounters(into[key], value);
    }
  }
}

}  // namespace

MergedFrame mergeShards(const std::vector<std::string>& paths) {
  if (paths.empty()) throw InputError("merge: no shard reports given");
  std::vector<nlohmann::json> reports;
  for (const std::string& p : paths) {
    nlohmann::json r = readReport(p);
    if (!r.contains("shard") || !r.contains("run_key")) {
      throw InputError(fmt::format("{}: not a shard's report (no shard or run_key: run it with --shard I/N)", p));
    }
    reports.push_back(std::move(r));
  }
  const nlohmann::json& key = reports.front()["run_key"];
  const int count = reports.front()["shard"]["count"];
  std::vector<int> owner(size_t(count), -1);
  for (size_t i = 0; i < reports.size(); ++i) {
    const nlohmann::json& r = reports[i];
    if (r["run_key"] != key) {
      for (const auto& [field, value] : key.items()) {
        if (r["run_key"].value(field, nlohmann::json()) != value) {
          throw InputError(fmt::format("{}: a shard of another run than {} ({}: {} against {})", paths[i], paths[0],
                                       field, r["run_key"].value(field, nlohmann::json()).dump(), value.dump()));
        }
      }
      throw InputError(fmt::format("{}: a shard of another run than {}", paths[i], paths[0]));
    }
    const int index = r["shard"]["index"];
    if (int(r["shard"]["count"]) != count || index < 0 || index >= count) {
      throw InputError(fmt::format("{}: shard {}/{} of a run cut in {}", paths[i], index, r["shard"]["count"].dump(), count));
    }
    if (owner[size_t(index)] >= 0) {
      throw InputError(fmt::format("{}: shard {} is also {}", paths[i], index, paths[size_t(owner[size_t(index)])]));
    }
    owner[size_t(index)] = int(i);
  }
  for (int s = 0; s < count; ++s) {
    if (owner[size_t(s)] < 0) throw InputError(fmt::format("merge: shard {}/{} is missing", s, count));
  }

  MergedFrame frame;
  nlohmann::json classes = nlohmann::json::object();
  nlohmann::json chips = nlohmann::json::array();
  std::vector<uint64_t> waveRays;
  uint64_t mismatches = 0, beyond = 0, selfHits = 0;
  for (int s = 0; s < count; ++s) {
    const std::string& path = paths[size_t(owner[size_t(s)])];
    const nlohmann::json& r = reports[size_t(owner[size_t(s)])];
    const size_t n = r["shard"]["samples"];
    std::ifstream in(samplesFileOf(path), std::ios::binary);
    std::vector<glm::vec3> hw(n), ref(n);
    in.read(reinterpret_cast<char*>(hw.data()), std::streamsize(n * sizeof(glm::vec3)));
    in.read(reinterpret_cast<char*>(ref.data()), std::streamsize(n * sizeof(glm::vec3)));
    if (!in || in.peek() != std::char_traits<char>::eof()) {
      throw InputError(fmt::format("{}: not the {} samples its report names", samplesFileOf(path), 2 * n));
    }
    frame.hardware.insert(frame.hardware.end(), hw.begin(), hw.end());
    frame.reference.insert(frame.reference.end(), ref.begin(), ref.end());
    for (const auto& [name, c] : r["classes"].items()) addCounters(classes[name], c);
    const std::vector<uint64_t> waves = r["wave_rays"];
    if (waveRays.size() < waves.size()) waveRays.resize(waves.size());
    for (size_t w = 0; w < waves.size(); ++w) waveRays[w] += waves[w];
    mismatches += r["mismatches"].get<uint64_t>();
    beyond += r["beyond_bound"].get<uint64_t>();
    selfHits += r["self_hits"].get<uint64_t>();
    chips.push_back({{"shard", s}, {"cycles", r["cycles"]}, {"units", r.value("units", 1)}});
  }
  const uint64_t total = reports.front()["shard"]["total_samples"];
  if (frame.hardware.size() != total) {
    throw InputError(fmt::format("merge: the shards hold {} samples of the frame's {}", frame.hardware.size(), total));
  }
  frame.report = key;
  frame.report.update({{"command", "merge"},
                       {"shards", count},
                       {"classes", classes},
                       {"wave_rays", waveRays},
                       {"mismatches", mismatches},
                       {"beyond_bound", beyond},
                       {"self_hits", selfHits},
                       {"image_rel_mse", relativeMse(frame.hardware, frame.reference)},
                       {"chips", chips},
                       {"cycles_note", "each shard ran on a chip of its own: its cycles are listed per shard under "
                                       "chips, and a class's cycles are the sum over separate chips"}});
  return frame;
}

}  // namespace lancer::cli
