#include "memory/config.h"

#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/error.h"

namespace lancer::mem {

const char* portName(Port port) {
  switch (port) {
    case Port::Node: return "node";
    case Port::Index: return "index";
    case Port::Triangle: return "triangle";
  }
  return "?";
}

const char* memoryKindName(MemoryKind kind) { return kind == MemoryKind::Fixed ? "fixed" : "hierarchy"; }

MemoryKind parseMemoryKind(const std::string& name) {
  if (name == "fixed") return MemoryKind::Fixed;
  if (name == "hierarchy") return MemoryKind::Hierarchy;
  throw InputError(fmt::format("--memory {}: expected fixed or hierarchy", name));
}

namespace {

bool powerOfTwo(int64_t v) { return v > 0 && (v & (v - 1)) == 0; }

[[noreturn]] void bad(const char* option, const std::string& value, const std::string& why) {
  throw InputError(fmt::format("{} {}: {}", option, value, why));
}

void atLeast(const char* option, int value, int least) {
  if (value < least) bad(option, std::to_string(value), fmt::format("must be at least {}", least));
}

// A cache of `kib` KiB in lines of `lineBytes`, `ways` ways: at least one
// line per way, and a power-of-two number of sets (the set is the line's low bits).
void checkCache(const char* level, const char* kibOption, const char* waysOption, int kib, int ways, int lineBytes) {
  atLeast(kibOption, kib, 1);
  atLeast(waysOption, ways, 1);
  const int64_t bytes = int64_t(kib) * 1024;
  if (bytes < lineBytes) {
    bad(kibOption, std::to_string(kib), fmt::format("the {} ({} bytes) is smaller than a line ({} bytes)", level, bytes, lineBytes));
  }
  const int64_t lines = bytes / lineBytes;
  if (lines % ways != 0 || !powerOfTwo(lines / ways)) {
    bad(kibOption, std::to_string(kib),
        fmt::format("the {} has {} lines of {} bytes in {} ways: its set count ({}) must be a power of two", level,
                    lines, lineBytes, ways, double(lines) / ways));
  }
}

}  // namespace

void MemoryConfig::validate() const {
  if (!(clockMhz > 0) || !std::isfinite(clockMhz)) bad("--clock-mhz", fmt::format("{}", clockMhz), "must be above 0");
  if (kind == MemoryKind::Fixed) {
    atLeast("--mem-latency", fixedLatency, 1);
    atLeast("--mem-jitter", fixedJitter, 0);
    return;
  }
  if (!powerOfTwo(l1.lineBytes) || l1.lineBytes < 8 || l1.lineBytes > 4096) {
    bad("--l1-line-bytes", std::to_string(l1.lineBytes), "must be a power of two from 8 to 4096");
  }
  checkCache("L1", "--l1-kib", "--l1-ways", l1.kib, l1.ways, l1.lineBytes);
  atLeast("--l1-mshrs", l1.mshrs, 1);
  atLeast("--l1-latency", l1.hitLatency, 1);
  checkCache("L2", "--l2-kib", "--l2-ways", l2.kib, l2.ways, l1.lineBytes);
  if (!powerOfTwo(l2.banks) || l2.banks > 64) bad("--l2-banks", std::to_string(l2.banks), "must be a power of two from 1 to 64");
  atLeast("--l2-latency", l2.latency, 1);
  atLeast("--l2-mshrs", l2.mshrs, 1);
  if (!(dram.gbps > 0) || !std::isfinite(dram.gbps)) {
    bad("--dram-gbps", fmt::format("{}", dram.gbps), "DRAM needs a bandwidth above 0 GB/s");
  }
  if (!(dram.latencyNs >= 0) || !std::isfinite(dram.latencyNs)) {
    bad("--dram-latency-ns", fmt::format("{}", dram.latencyNs), "must be 0 or more");
  }
  if (!powerOfTwo(dram.channels) || dram.channels > 64) {
    bad("--dram-channels", std::to_string(dram.channels), "must be a power of two from 1 to 64");
  }
  atLeast("--dram-queue", dram.queueDepth, 1);
}

void to_json(nlohmann::json& j, const MemoryConfig& c) {
  j = {{"kind", memoryKindName(c.kind)}};
  if (c.kind == MemoryKind::Fixed) {
    j["latency_cycles"] = c.fixedLatency;
    j["jitter_cycles"] = c.fixedJitter;
    return;
  }
  j["l1"] = {{"kib", c.l1.kib}, {"ways", c.l1.ways}, {"line_bytes", c.l1.lineBytes}, {"mshrs", c.l1.mshrs},
             {"hit_latency_cycles", c.l1.hitLatency}, {"per", "port (node, index, triangle)"}};
  j["l2"] = {{"kib", c.l2.kib}, {"ways", c.l2.ways}, {"banks", c.l2.banks}, {"latency_cycles", c.l2.latency},
             {"mshrs_per_bank", c.l2.mshrs}};
  j["dram"] = {{"gbps", c.dram.gbps}, {"latency_ns", c.dram.latencyNs}, {"channels", c.dram.channels},
               {"queue_depth", c.dram.queueDepth}};
}

}  // namespace lancer::mem
