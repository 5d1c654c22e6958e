#include "memory/ray_queues.h"

#include <algorithm>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/error.h"

namespace lancer::mem {

void RayQueueConfig::validate() const {
  if (kib < 1 || kib > (1 << 20)) throw InputError(fmt::format("--queue-kib {}: use 1..{}", kib, 1 << 20));
  if (bytesPerCycle < 1 || bytesPerCycle > 4096) {
    throw InputError(fmt::format("--queue-bytes-per-cycle {}: use 1..4096", bytesPerCycle));
  }
  if (wordBytes < 1) throw InputError(fmt::format("queue word of {} bytes: at least 1", wordBytes));
  if (!(launchBelow > 0 && launchBelow <= 1)) {
    throw InputError(fmt::format("--queue-launch-below {}: a fraction of the queue memory, in (0, 1]", launchBelow));
  }
}

void to_json(nlohmann::json& j, const RayQueueConfig& c) {
  j = {{"kib", c.kib}, {"bytes_per_cycle", c.bytesPerCycle}, {"word_bytes", c.wordBytes},
       {"launch_below", c.launchBelow}};
}

RayQueueStats& RayQueueStats::operator+=(const RayQueueStats& o) {
  launched += o.launched;
  suspensions += o.suspensions;
  bytesWritten += o.bytesWritten;
  bytesRead += o.bytesRead;
  overflows += o.overflows;
  overflowBytes += o.overflowBytes;
  peakBytes = std::max(peakBytes, o.peakBytes);
  byteCycles += o.byteCycles;
  cycles += o.cycles;
  blockSwitches += o.blockSwitches;
  writeWaitCycles += o.writeWaitCycles;
  readWaitCycles += o.readWaitCycles;
  return *this;
}

void to_json(nlohmann::json& j, const RayQueueStats& s) {
  j = {{"launched", s.launched},
       {"suspensions", s.suspensions},
       {"bytes_written", s.bytesWritten},
       {"bytes_read", s.bytesRead},
       {"overflows", s.overflows},
       {"overflow_dram_bytes", s.overflowBytes},
       {"peak_bytes", s.peakBytes},
       {"mean_bytes", s.cycles ? double(s.byteCycles) / double(s.cycles) : 0.0},
       {"block_switches", s.blockSwitches},
       {"write_wait_cycles", s.writeWaitCycles},
       {"read_wait_cycles", s.readWaitCycles}};
}

RayQueues::RayQueues(const RayQueueConfig& config, size_t fresh, MemorySystem& memory)
    : config_(config), memory_(memory), fresh_(fresh) {}

uint64_t RayQueues::recordBytes(int bits) const {
  const uint64_t word = uint64_t(config_.wordBytes);
  return (uint64_t(bits) + 8 * word - 1) / (8 * word) * word;
}

void RayQueues::suspend(size_t segment, uint32_t block, int bits) {
  const uint64_t now = memory_.cycle();
  const uint64_t bytes = recordBytes(bits);
  ++stats_.suspensions;
  Record r{segment, block, bytes, now};
  if (onChip_ + bytes > uint64_t(config_.kib) * 1024) {
    // No room on chip: the record goes to DRAM, and comes back from there.
    ++stats_.overflows;
    stats_.overflowBytes += bytes;
    r.bytes = 0;
    r.readyAt = memory_.transfer(bytes);
    r.dramBytes = bytes;
  } else {
    const uint64_t start = std::max(now, writeFree_);
    stats_.writeWaitCycles += start - now;
    writeFree_ = start + (bytes + uint64_t(config_.bytesPerCycle) - 1) / uint64_t(config_.bytesPerCycle);
    r.readyAt = writeFree_;
    onChip_ += bytes;
    stats_.bytesWritten += bytes;
    stats_.peakBytes = std::max(stats_.peakBytes, onChip_);
  }
  writing_.emplace(r.readyAt, r);
}

void RayQueues::endCycle() {
  const uint64_t now = memory_.cycle();
  // Records join their queues once written, in the order their writes
  // finish (ties: the order they were suspended).
  while (!writing_.empty() && writing_.begin()->first <= now) {
    const Record& r = writing_.begin()->second;
    queues_[r.block].push_back(r);
    writing_.erase(writing_.begin());
    ++waiting_;
  }
  stats_.byteCycles += onChip_;
  ++stats_.cycles;
}

bool RayQueues::pick() {
  if (onBlock_) {
    const auto q = queues_.find(block_);
    if (q != queues_.end() && !q->second.empty()) return true;
  }
  const bool freshLeft = launched_ < fresh_;
  if (freshLeft && (double(onChip_) < config_.launchBelow * config_.kib * 1024 || waiting_ == 0)) {
    onBlock_ = false;
    return true;
  }
  if (waiting_ == 0) return false;
  auto fullest = queues_.end();
  for (auto q = queues_.begin(); q != queues_.end(); ++q) {
    if (!q->second.empty() && (fullest == queues_.end() || q->second.size() > fullest->second.size())) fullest = q;
  }
  onBlock_ = true;
  block_ = fullest->first;
  ++stats_.blockSwitches;
  return true;
}

void RayQueues::handOut(size_t count, std::vector<Handed>& out) {
  const uint64_t now = memory_.cycle();
  out.clear();
  if (!pick()) return;
  if (!onBlock_) {
    for (; out.size() < count && launched_ < fresh_; ++launched_) out.push_back({launched_, now});
    stats_.launched += out.size();
    return;
  }
  std::deque<Record>& q = queues_[block_];
  while (out.size() < count && !q.empty()) {
    const Record r = q.front();
    q.pop_front();
    --waiting_;
    uint64_t readyAt;
    if (r.dramBytes != 0) {
      stats_.overflowBytes += r.dramBytes;
      readyAt = memory_.transfer(r.dramBytes);
    } else {
      const uint64_t start = std::max(now, readFree_);
      stats_.readWaitCycles += start - now;
      readFree_ = start + (r.bytes + uint64_t(config_.bytesPerCycle) - 1) / uint64_t(config_.bytesPerCycle);
      readyAt = readFree_;
      onChip_ -= r.bytes;
      stats_.bytesRead += r.bytes;
    }
    out.push_back({r.segment, readyAt});
  }
  if (q.empty()) queues_.erase(block_);
}

bool RayQueues::empty() const { return launched_ == fresh_ && waiting_ == 0 && writing_.empty(); }

}  // namespace lancer::mem
