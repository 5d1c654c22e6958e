#include "memory/system.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <deque>
#include <unordered_map>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/error.h"

#include "golden/stimulus.h"
#include "memory/cache.h"

namespace lancer::mem {

MemoryStats::Cache& MemoryStats::Cache::operator+=(const Cache& o) {
  accesses += o.accesses;
  hits += o.hits;
  misses += o.misses;
  merges += o.merges;
  return *this;
}

MemoryStats::Cache MemoryStats::l1Total() const {
  Cache total;
  for (const auto& unit : l1) {
    for (const Cache& c : unit) total += c;
  }
  return total;
}

MemoryStats& MemoryStats::operator+=(const MemoryStats& o) {
  if (l1.size() < o.l1.size()) l1.resize(o.l1.size());
  for (size_t u = 0; u < o.l1.size(); ++u) {
    for (int p = 0; p < kPorts; ++p) l1[u][size_t(p)] += o.l1[u][size_t(p)];
  }
  l2 += o.l2;
  reads += o.reads;
  dramLines += o.dramLines;
  dramBytes += o.dramBytes;
  transferBytes += o.transferBytes;
  footprintLines += o.footprintLines;
  footprintBytes += o.footprintBytes;
  l1FullCycles += o.l1FullCycles;
  l2BankWaitCycles += o.l2BankWaitCycles;
  l2MshrFullCycles += o.l2MshrFullCycles;
  dramQueueFullCycles += o.dramQueueFullCycles;
  dramQueueWaitCycles += o.dramQueueWaitCycles;
  return *this;
}

static nlohmann::json cacheJson(const MemoryStats::Cache& c) {
  return {{"accesses", c.accesses}, {"hits", c.hits}, {"misses", c.misses}, {"merges", c.merges},
          {"hit_rate", c.hitRate()}};
}

void to_json(nlohmann::json& j, const MemoryStats& s) {
  j = {{"reads", s.reads},
       {"dram_lines", s.dramLines},
       {"dram_bytes", s.dramBytes},
       {"transfer_bytes", s.transferBytes},
       {"footprint_lines", s.footprintLines}, {"footprint_bytes", s.footprintBytes},
       {"stall_cycles",
        {{"l1_full", s.l1FullCycles},
         {"l2_bank_wait", s.l2BankWaitCycles},
         {"l2_mshr_full", s.l2MshrFullCycles},
         {"dram_queue_full", s.dramQueueFullCycles},
         {"dram_queue_wait", s.dramQueueWaitCycles}}}};
  if (!s.l1.empty()) {
    j["l1"] = cacheJson(s.l1Total());
    nlohmann::json ports = nlohmann::json::object();
    for (int p = 0; p < kPorts; ++p) {
      MemoryStats::Cache c;
      for (const auto& unit : s.l1) c += unit[size_t(p)];
      ports[portName(Port(p))] = cacheJson(c);
    }
    j["l1_by_port"] = ports;
    j["l2"] = cacheJson(s.l2);
  }
}

namespace {

// Today's model: each port of each unit a fx::MemoryReadPort (fixed latency,
// seeded jitter, in order). Unit 0's seeds are the single-unit runs' own
// (seed*3+1, +2, +3), so a chip of one unit is cycle for cycle that run.
class FixedMemory final : public MemorySystem {
 public:
  FixedMemory(const MemoryConfig& c, int units) : MemorySystem(units), ports_(size_t(units)), latency_(c.fixedLatency) {
    for (int u = 0; u < units; ++u) {
      const uint64_t seed = unitSeed(c.seed, u);
      for (int p = 0; p < kPorts; ++p) ports_[size_t(u)][size_t(p)].restart(c.fixedLatency, c.fixedJitter, seed * 3 + uint64_t(p) + 1);
    }
  }
  bool ready(int, Port) const override { return true; }
  void request(int unit, Port port, uint32_t record, uint32_t tag) override {
    at(unit, port).request(now_, record, tag);
    ++reads_[size_t(unit)];
  }
  bool response(int unit, Port port, uint32_t& record, uint32_t& tag) override {
    return at(unit, port).respond(now_, record, tag);
  }
  void blocked(int, Port) override {}
  // No DRAM here: a transfer takes the fixed latency, and costs no bandwidth.
  uint64_t transfer(uint64_t bytes) override {
    transferBytes_ += bytes;
    return now_ + uint64_t(latency_);
  }
  void tick() override { ++now_; }
  bool idle() const override {
    for (const auto& unit : ports_) {
      for (const fx::MemoryReadPort& p : unit) {
        if (!p.idle()) return false;
      }
    }
    return true;
  }
  MemoryStats stats() const override {
    MemoryStats s;  // no caches: reads only
    for (uint64_t r : reads_) s.reads += r;
    s.transferBytes = transferBytes_;
    return s;
  }
  void clearStats() override {
    std::fill(reads_.begin(), reads_.end(), 0);
    transferBytes_ = 0;
  }

 private:
  fx::MemoryReadPort& at(int unit, Port port) { return ports_[size_t(unit)][size_t(port)]; }
  std::vector<std::array<fx::MemoryReadPort, kPorts>> ports_;
  std::vector<uint64_t> reads_ = std::vector<uint64_t>(ports_.size(), 0);  // per unit: request() runs on the unit's thread
  int latency_;
  uint64_t transferBytes_ = 0;
};

// The hierarchy (docs/chip.md): per unit and port an L1 (tags, MSHRs, an
// in-order response queue), one L2 of `banks` banks, DRAM channels.
class HierarchyMemory final : public MemorySystem {
 public:
  HierarchyMemory(const MemoryConfig& c, const AddressMap& map, int units)
      : MemorySystem(units), config_(c), map_(map), banks_(size_t(c.l2.banks)), channels_(size_t(c.dram.channels)),
        l2Tags_(uint64_t(c.l2.kib) * 1024, c.l2.ways, c.l1.lineBytes) {
    lineBytes_ = uint64_t(c.l1.lineBytes);
    firstLine_ = AddressMap::kBase / lineBytes_;
    touched_ = std::vector<std::atomic<uint64_t>>(size_t((map.end() / lineBytes_ + 1 - firstLine_ + 63) / 64));
    for (int p = 0; p < kPorts; ++p) {
      const uint32_t bytes = map.maxReadBytes(Port(p));
      maxLines_[size_t(p)] = int((bytes + lineBytes_ - 2) / lineBytes_ + 1);  // a read at any offset
      if (maxLines_[size_t(p)] > c.l1.mshrs) {
        throw InputError(fmt::format("--l1-mshrs {}: a read of the {} ({} bytes) may span {} lines of {} bytes, "
                                     "and an L1 takes a read only with an MSHR for each",
                                     c.l1.mshrs, map.region(Port(p)).name, bytes, maxLines_[size_t(p)], lineBytes_));
      }
    }
    l1s_.reserve(size_t(units) * kPorts);
    for (int i = 0; i < units * kPorts; ++i) l1s_.emplace_back(c.l1);
    periodPs_ = 1e6 / c.clockMhz;
    transferPs_ = double(lineBytes_) * double(c.dram.channels) / c.dram.gbps * 1000.0;
    latencyPs_ = c.dram.latencyNs * 1000.0;
    stats_.l1.assign(size_t(units), {});
    updateReady();
  }

  bool ready(int unit, Port port) const override { return l1(unit, port).ready; }

  // The L1's lookup, in the cycle of the request: a hit is answered
  // hitLatency cycles later; a miss takes an MSHR (or merges into the one of
  // its line) and leaves for the L2 after the tag check.
  void request(int unit, Port port, uint32_t record, uint32_t tag) override {
    L1& c = l1(unit, port);
    const ReadSpan span = map_.span(port, record);
    const uint64_t seq = c.headSeq + c.queue.size();
    Entry& e = c.queue.emplace_back(Entry{record, tag, 0, now_ + uint64_t(config_.l1.hitLatency)});
    for (uint64_t line = span.first / lineBytes_; line <= (span.first + span.bytes - 1) / lineBytes_; ++line) {
      touch(line);
      ++c.stats.accesses;
      if (c.tags.lookup(line)) {
        ++c.stats.hits;
        continue;
      }
      ++e.waiting;
      std::vector<uint64_t>* waiters = c.mshrs.find(line);
      const bool fresh = waiters == nullptr;
      if (fresh) waiters = &c.mshrs.add(line);
      waiters->push_back(seq);
      if (fresh) {
        ++c.stats.misses;
        c.outbound.push_back(line);
      } else {
        ++c.stats.merges;
      }
    }
  }

  bool response(int unit, Port port, uint32_t& record, uint32_t& tag) override {
    L1& c = l1(unit, port);
    if (c.queue.empty()) return false;
    const Entry& head = c.queue.front();
    if (head.waiting > 0 || head.readyAt > now_) return false;
    record = head.record;
    tag = head.tag;
    c.queue.pop_front();
    ++c.headSeq;
    ++c.reads;
    return true;
  }

  void blocked(int unit, Port port) override { ++l1(unit, port).refusedCycles; }

  // Line by line over the channels in turn, each line after the channel's
  // work so far (a miss later waits behind it): the same bandwidth as the
  // caches' lines, counted in the DRAM bytes.
  uint64_t transfer(uint64_t bytes) override {
    double donePs = nowPs();
    for (uint64_t moved = 0; moved < bytes; moved += lineBytes_) {
      Channel& ch = channels_[nextTransferChannel_];
      nextTransferChannel_ = (nextTransferChannel_ + 1) % channels_.size();
      const double start = std::max(nowPs(), ch.freePs);
      ch.freePs = start + transferPs_;
      donePs = std::max(donePs, start + latencyPs_ + transferPs_);
      stats_.dramBytes += lineBytes_;
      stats_.transferBytes += lineBytes_;
    }
    return uint64_t(std::ceil(donePs / periodPs_));
  }

  void tick() override {
    const uint64_t lookupAt = now_ + uint64_t(config_.l1.hitLatency);
    for (size_t i = 0; i < l1s_.size(); ++i) {
      for (uint64_t line : l1s_[i].outbound) banks_[bankOf(line)].queue.push_back({int(i), line, lookupAt});
      l1s_[i].outbound.clear();
    }
    for (Bank& b : banks_) serveBank(b);
    finishDram();
    for (L1& c : l1s_) fillL1(c);
    ++now_;
    updateReady();
  }

  bool idle() const override {
    for (const L1& c : l1s_) {
      if (!c.queue.empty() || !c.outbound.empty() || !c.fills.empty()) return false;
    }
    for (const Bank& b : banks_) {
      if (!b.queue.empty() || !b.mshrs.empty()) return false;
    }
    for (const Channel& ch : channels_) {
      if (!ch.requests.empty()) return false;
    }
    return true;
  }

  void clearStats() override {
    for (std::atomic<uint64_t>& w : touched_) w.store(0, std::memory_order_relaxed);
    stats_ = MemoryStats{};
    stats_.l1.assign(size_t(units_), {});
    for (L1& c : l1s_) {
      c.stats = {};
      c.reads = c.refusedCycles = 0;
    }
  }

  MemoryStats stats() const override {
    MemoryStats s = stats_;
    for (size_t i = 0; i < l1s_.size(); ++i) {
      s.l1[i / kPorts][i % kPorts] = l1s_[i].stats;
      s.reads += l1s_[i].reads;
      s.l1FullCycles += l1s_[i].refusedCycles;
    }
    for (const std::atomic<uint64_t>& w : touched_) s.footprintLines += uint64_t(std::popcount(w.load(std::memory_order_relaxed)));
    s.footprintBytes = s.footprintLines * lineBytes_;
    return s;
  }

 private:
  // A request in an L1's in-order response queue.
  struct Entry {
    uint32_t record, tag;
    int waiting;       // its lines still to come from the L2
    uint64_t readyAt;  // the cycle its data is there (once waiting == 0)
  };
  static constexpr size_t kQueueEntries = 32;  // requests in flight per L1 (the response queue)

  // An L1's MSHRs: its few lines in flight, each with the queue entries that
  // await it, searched in place. Entries keep their waiter lists' storage when
  // freed, so the L1's path allocates nothing once warm.
  class MshrFile {
   public:
    std::vector<uint64_t>* find(uint64_t line) {
      for (size_t i = 0; i < used_; ++i) {
        if (slots_[i].line == line) return &slots_[i].waiters;
      }
      return nullptr;
    }
    std::vector<uint64_t>& add(uint64_t line) {
      if (used_ == slots_.size()) slots_.emplace_back();
      Slot& s = slots_[used_++];
      s.line = line;
      s.waiters.clear();
      return s.waiters;
    }
    void erase(uint64_t line) {
      for (size_t i = 0; i < used_; ++i) {
        if (slots_[i].line == line) {
          std::swap(slots_[i], slots_[--used_]);
          return;
        }
      }
    }
    size_t size() const { return used_; }

   private:
    struct Slot {
      uint64_t line = 0;
      std::vector<uint64_t> waiters;
    };
    std::vector<Slot> slots_;
    size_t used_ = 0;
  };

  struct L1 {
    explicit L1(const L1Config& c) : tags(uint64_t(c.kib) * 1024, c.ways, c.lineBytes), mshrCap(size_t(c.mshrs)) {}
    CacheTags tags;
    size_t mshrCap;
    std::deque<Entry> queue;
    uint64_t headSeq = 0;  // the sequence number of queue.front()
    MshrFile mshrs;  // line -> the queue entries (seq) awaiting it
    std::vector<uint64_t> outbound;                              // this cycle's misses, to the L2 at tick()
    std::deque<std::pair<uint64_t, uint64_t>> fills;             // (cycle, line) from the L2, in time order
    bool ready = true;
    uint64_t reads = 0, refusedCycles = 0;
    MemoryStats::Cache stats;
  };
  struct LineRequest {
    int l1;         // index into l1s_
    uint64_t line;
    uint64_t at;    // the first cycle the bank may look it up
  };
  struct Bank {
    std::deque<LineRequest> queue;
    std::unordered_map<uint64_t, std::vector<int>> mshrs;  // line -> the L1s awaiting it
  };
  struct DramRequest {
    uint64_t line;
    double startPs, donePs;
  };
  struct Channel {
    std::deque<DramRequest> requests;  // in order of service
    double freePs = 0;                 // when its data bus is free
  };

  L1& l1(int unit, Port port) { return l1s_[size_t(unit) * kPorts + size_t(port)]; }
  const L1& l1(int unit, Port port) const { return l1s_[size_t(unit) * kPorts + size_t(port)]; }
  size_t bankOf(uint64_t line) const { return size_t(line % banks_.size()); }
  size_t channelOf(uint64_t line) const { return size_t((line / banks_.size()) % channels_.size()); }
  double nowPs() const { return double(now_) * periodPs_; }
  // The line into the run's footprint. Units may call request() on threads of
  // their own: the bitmap's words are set atomically (a union, whatever the order).
  void touch(uint64_t line) {
    const uint64_t i = line - firstLine_;
    std::atomic<uint64_t>& word = touched_[size_t(i / 64)];
    const uint64_t bit = uint64_t(1) << (i % 64);
    if (!(word.load(std::memory_order_relaxed) & bit)) word.fetch_or(bit, std::memory_order_relaxed);
  }

  // One lookup per bank and cycle, oldest first: a hit goes back to its L1
  // `latency` cycles later; a miss takes an MSHR and a place in its DRAM
  // channel's queue, or waits for them at the head of the bank.
  void serveBank(Bank& b) {
    if (b.queue.empty() || b.queue.front().at > now_) return;
    for (size_t i = 1; i < b.queue.size() && b.queue[i].at <= now_; ++i) ++stats_.l2BankWaitCycles;
    const LineRequest r = b.queue.front();
    if (l2Tags_.lookup(r.line)) {
      ++stats_.l2.accesses;
      ++stats_.l2.hits;
      sendFill(r.l1, r.line, now_ + uint64_t(config_.l2.latency));
    } else if (auto m = b.mshrs.find(r.line); m != b.mshrs.end()) {
      ++stats_.l2.accesses;
      ++stats_.l2.merges;
      m->second.push_back(r.l1);
    } else if (b.mshrs.size() >= size_t(config_.l2.mshrs)) {
      ++stats_.l2MshrFullCycles;
      return;
    } else {
      Channel& ch = channels_[channelOf(r.line)];
      size_t queued = 0;
      for (const DramRequest& d : ch.requests) queued += d.startPs > nowPs() ? 1 : 0;
      if (queued >= size_t(config_.dram.queueDepth)) {
        ++stats_.dramQueueFullCycles;
        return;
      }
      ++stats_.l2.accesses;
      ++stats_.l2.misses;
      b.mshrs[r.line].push_back(r.l1);
      const double start = std::max(nowPs(), ch.freePs);
      ch.freePs = start + transferPs_;
      ch.requests.push_back({r.line, start, start + latencyPs_ + transferPs_});
    }
    b.queue.pop_front();
  }

  // DRAM's lines whose last byte arrived by this cycle: into the L2, and on
  // to every L1 awaiting them.
  void finishDram() {
    for (Channel& ch : channels_) {
      for (const DramRequest& d : ch.requests) {
        if (d.startPs > nowPs()) stats_.dramQueueWaitCycles += 1;
      }
      while (!ch.requests.empty() && ch.requests.front().donePs <= nowPs()) {
        const uint64_t line = ch.requests.front().line;
        ch.requests.pop_front();
        ++stats_.dramLines;
        stats_.dramBytes += lineBytes_;
        l2Tags_.insert(line);
        Bank& b = banks_[bankOf(line)];
        const auto m = b.mshrs.find(line);
        for (int l1 : m->second) sendFill(l1, line, now_ + uint64_t(config_.l2.latency));
        b.mshrs.erase(m);
      }
    }
  }

  void sendFill(int l1, uint64_t line, uint64_t at) { l1s_[size_t(l1)].fills.emplace_back(at, line); }

  // One fill per L1 and cycle: the line enters the tags and its waiting
  // requests are answered from the next cycle.
  void fillL1(L1& c) {
    if (c.fills.empty() || c.fills.front().first > now_) return;
    const uint64_t line = c.fills.front().second;
    c.fills.pop_front();
    c.tags.insert(line);
    for (uint64_t seq : *c.mshrs.find(line)) {
      Entry& e = c.queue[size_t(seq - c.headSeq)];
      --e.waiting;
      e.readyAt = std::max(e.readyAt, now_ + 1);
    }
    c.mshrs.erase(line);
  }

  void updateReady() {
    for (size_t i = 0; i < l1s_.size(); ++i) {
      L1& c = l1s_[i];
      c.ready = c.queue.size() < kQueueEntries && c.mshrs.size() + size_t(maxLines_[i % kPorts]) <= c.mshrCap;
    }
  }

  MemoryConfig config_;
  AddressMap map_;
  uint64_t lineBytes_;
  uint64_t firstLine_;                          // the image's first line (AddressMap::kBase)
  std::vector<std::atomic<uint64_t>> touched_;  // a bit per line of the image: read in this run
  std::array<int, kPorts> maxLines_{};
  std::vector<L1> l1s_;  // unit-major: l1s_[unit * kPorts + port]
  std::vector<Bank> banks_;
  std::vector<Channel> channels_;
  size_t nextTransferChannel_ = 0;
  CacheTags l2Tags_;
  double periodPs_, transferPs_, latencyPs_;
  MemoryStats stats_;
};

}  // namespace

std::unique_ptr<MemorySystem> MemorySystem::make(const MemoryConfig& config, const AddressMap& map, int units) {
  if (config.kind == MemoryKind::Fixed) return std::make_unique<FixedMemory>(config, units);
  return std::make_unique<HierarchyMemory>(config, map, units);
}

}  // namespace lancer::mem
