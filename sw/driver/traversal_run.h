#pragma once

// The run loop of a chip of traversal units on the chip's memory system
// (docs/chip.md), over any clocked model of a unit whose ports are plain
// members under the RTL's names:
//   VerilatedUnit<Top>  (verilated_unit.h)   the Verilated RTL, "rtl"
//   ModelUnit<Model>    (model_unit.h)       a SystemC cycle model on value
//                                            ports, "systemc" (the fast path)
// A Clocked provides top_type, kModel (the model's name, for messages),
// top(), select(), settle() (the inputs through the combinational logic),
// tick() (the rising edge), reset(idle), openWave(path) and closeWave().
//
// TraversalTop<Top>, specialized once per clocked top next to the device's
// explicit instantiation (LANCER_VERILATED_TRAVERSAL_UNIT, and
// LANCER_MODEL_TRAVERSAL_UNIT in systemc_traversal_device_impl.h), defines
// (all static, inline) only what names the top's own members:
//   Desc               the unit's descriptor (golden/unit.h): names, records,
//                      node packing, configuration, image checks
//   kMaxSlots          RaysInFlight, from the unit's compile definition
//   nodePort(top)      std::tie of the node port: req valid, addr, tag,
//                      req ready, rsp valid, data, tag
//   configPort(top)    its configuration port besides cfg_slots_i
// Every member is inlined into the loop; nothing is allocated per cycle.

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <thread>
#include <tuple>
#include <type_traits>
#include <vector>

#include <fmt/format.h>

#include "common/error.h"
#include "common/rt_trav_cycle.h"
#include "driver/chip.h"
#include "driver/cycle_barrier.h"
#include "driver/traversal_device.h"
#include "driver/verilated_port.h"
#include "driver/wave_file.h"
#include "golden/record_bits.h"
#include "golden/stimulus.h"

namespace lancer {

template <class Top>
struct TraversalTop;

// InputError for options a clocked traversal unit (`model`: "rtl", "systemc")
// cannot run: raysInFlight outside 0..maxSlots, a memory latency below 1, a
// negative jitter. `unit` names it ("grid", "octree"), `cmakeVariable` the
// build option for more slots.
inline void checkTraversalOptions(const TraversalRunOptions& options, std::string_view model, int maxSlots,
                                  const char* unit, const char* cmakeVariable) {
  if (options.raysInFlight < 0 || options.raysInFlight > maxSlots) {
    throw InputError(fmt::format("rays in flight {} is out of range: the {} {} unit was built with {} ray slots "
                                 "(use 1..{}, or 0 for all; rebuild with -D{} for more)",
                                 options.raysInFlight, model == "rtl" ? "RTL" : "SystemC", unit, maxSlots, maxSlots, cmakeVariable));
  }
  if (options.memLatency < 1 || options.memLatencyJitter < 0) {
    throw InputError(fmt::format("memory latency {} (jitter {}) is out of range: latency >= 1, jitter >= 0",
                                 options.memLatency, options.memLatencyJitter));
  }
  checkChipOptions(options);
}

// InputError for an image with quadrics on a model of the unit without
// rt_quadric (`model`: the mixed system, whose rt_isect is the Verilated one).
template <class Image>
void refuseQuadrics(const Image& image, std::string_view model, const char* unit) {
  if (!image.quadrics.empty()) {
    throw InputError(fmt::format("the {} model of the {} unit has no quadric pipeline beside its Verilated "
                                 "rt_isect, and the scene has {} quadrics: use --model systemc or rtl, or "
                                 "--quadrics tessellate",
                                 model, unit, image.quadrics.size()));
  }
}

// The seeded stream stimulus of one unit of a traversal-unit run, drawn in
// the same order by every model: per cycle one draw each for the input bubble
// (only while no ray is on offer), the result stall and the visit stall. Unit
// u draws from mem::unitSeed(seed, u) (unit 0: the stream's seed).
// (The memory ports are the chip's memory system: memory/system.h.)
struct TraversalStimulus {
  TraversalStimulus(const TraversalRunOptions& o, int unit)
      : rng(mem::unitSeed(o.stream.seed, unit)),
        idle(o.stream.inputIdleProbability, rng),
        stallRes(o.stream.outputStallProbability, rng),
        stallVisit(o.stream.outputStallProbability, rng) {}
  TraversalStimulus(const TraversalStimulus&) = delete;
  TraversalStimulus& operator=(const TraversalStimulus&) = delete;

  std::mt19937_64 rng;
  fx::Coin idle, stallRes, stallVisit;
};

// No progress (a ray accepted, a test, a visit or a result) for this many cycles ends a run.
inline constexpr uint64_t kTraversalWatchdogCycles = 1000000;

namespace trav_detail {

// The unit's configuration port for `image` (an empty Image at reset).
template <class Top, class Image>
void configure(Top& top, const Image& image) {
  using Desc = typename TraversalTop<Top>::Desc;
  std::array<uint32_t, size_t(fx::wireWords(fx::kCfgBitsOf<Desc>))> wire{};
  fx::packConfig<Desc>(image, wire);
  auto& port = TraversalTop<Top>::configPort(top);
  static_assert(portWords<std::remove_reference_t<decltype(port)>>() == wire.size(),
                "the configuration port does not match the descriptor's kCfgFields: rebuild rt_pkg");
  writePort(port, wire.data(), wire.size());
}

// Bit offset of field `index` in a record: the first field is the most significant.
constexpr int fieldLsb(std::span<const fx::FieldSpec> fields, size_t index) {
  int lsb = 0;
  for (size_t i = index + 1; i < fields.size(); ++i) lsb += fields[i].width * fields[i].count;
  return lsb;
}

// Every input at its idle value: nothing offered, nothing taken, the memory
// ports ready and silent, all slots, the unit's idle configuration.
template <class Top>
void idleInputs(Top& top) {
  using Unit = TraversalTop<Top>;
  auto [reqValid, reqAddr, reqTag, reqReady, rspValid, rspData, rspTag] = Unit::nodePort(top);
  top.ray_valid_i = 0;
  top.res_ready_i = 0;
  top.visit_ready_i = 0;
  reqReady = 1;
  top.idx_req_ready_i = 1;
  top.tri_req_ready_i = 1;
  rspValid = 0;
  top.idx_rsp_valid_i = 0;
  top.tri_rsp_valid_i = 0;
  top.quadric_rsp_valid_i = 0;
  top.cfg_slots_i = Unit::kMaxSlots;
  configure(top, typename Unit::Desc::Image{});
}



// The image as the unit's ports carry it, packed once per run and read by
// every unit of the chip.
template <class Top, class Image>
struct PortImage {
  using Desc = typename TraversalTop<Top>::Desc;
  static constexpr size_t kTriWords = fx::kIsectTriWords;
  static constexpr size_t kQuadricWords = size_t(fx::wireWords(fx::kIsectQuadricBits));
  static constexpr size_t kNodeWords = size_t(fx::wireWords(fx::kNodeBitsOf<Desc>));
  static constexpr size_t kGroupWords = Desc::kGroup * kNodeWords;

  explicit PortImage(const Image& im) : image(im), nodes(Desc::nodes(im)) {
    nodeWire.resize(nodes.size() * kNodeWords);
    for (size_t i = 0; i < nodes.size(); ++i) {
      fx::packNode<Desc>(nodes[i], std::span<uint32_t>(nodeWire).subspan(kNodeWords * i, kNodeWords));
    }
    triWire.resize(image.triangles.size() * kTriWords);
    for (size_t i = 0; i < image.triangles.size(); ++i) {
      fx::packWire(image.triangles[i], std::span<uint32_t>(triWire).subspan(i * kTriWords, kTriWords));
    }
    quadricWire.resize(image.quadrics.size() * kQuadricWords);
    for (size_t i = 0; i < image.quadrics.size(); ++i) {
      fx::packWire(image.quadrics[i], std::span<uint32_t>(quadricWire).subspan(i * kQuadricWords, kQuadricWords));
    }
  }

  const Image& image;
  const std::remove_cvref_t<decltype(Desc::nodes(std::declval<const Image&>()))>& nodes;
  std::vector<uint32_t> nodeWire, triWire, quadricWire;
};

// What the units of a run share: the rays and their traces, the walks, and
// the dispatcher. A walk is a ray's way through a unit from its offer to its
// result: a ray's first walk has the ray's index as its id; under the treelet
// schedule a walk set aside is resumed as a new walk, with the next id
// (rays.size() + k for the k-th). Each walk's record is written only by the
// unit that took it; walks are added only between cycles (addResumed).
struct ChipRays {
  ChipRays(std::span<const fx::QRay> r, std::vector<fx::TraversalTrace>& t, int units, int batch)
      : rays(r), traces(t), owner(r.size(), -1), finished(r.size(), 0), resultElements(r.size(), 0),
        dispatcher(r.size(), units, batch) {}
  std::span<const fx::QRay> rays;
  std::vector<fx::TraversalTrace>& traces;
  std::deque<int> owner;  // per walk: the unit that took it (-1: none yet)
  std::deque<uint8_t> finished;
  std::deque<uint32_t> resultElements;
  // A resumed walk: its ray, the walk record it resumes (the unit's walk
  // record, as the result port gave it), its visits.
  struct Resumed {
    size_t ray;
    std::vector<uint32_t> walk;
    std::vector<uint32_t> visits;
  };
  std::deque<Resumed> resumed;
  Dispatcher dispatcher;

  size_t walks() const { return owner.size(); }
  size_t rayOf(size_t walk) const { return walk < rays.size() ? walk : resumed[walk - rays.size()].ray; }
  const Resumed* resumedWalk(size_t walk) const { return walk < rays.size() ? nullptr : &resumed[walk - rays.size()]; }
  std::vector<uint32_t>& visitsOf(size_t walk) {
    return walk < rays.size() ? traces[walk].visits : resumed[walk - rays.size()].visits;
  }
  size_t addResumed(size_t ray, std::vector<uint32_t> walk) {
    resumed.push_back(Resumed{ray, std::move(walk), {}});
    owner.push_back(-1);
    finished.push_back(0);
    resultElements.push_back(0);
    return walks() - 1;
  }
};

// A walk a unit set aside in this cycle, for the ray queues at its end.
struct SuspendedWalk {
  size_t walk;
  std::vector<uint32_t> record;
};

// One Verilated unit of a chip, cycle by cycle: it offers the rays the
// dispatcher hands it, serves its three memory ports from the chip's memory
// system, takes its visits and results. cycle() touches only this unit's
// state, its own rays' traces and the memory system's calls for this unit,
// so the units of a chip may run it on threads of their own. Every member is
// inlined into the loop; nothing is allocated per cycle.
template <class Clocked, class Image>
class UnitRun {
  using Top = typename Clocked::top_type;
  using Unit = TraversalTop<Top>;
  using Desc = typename Unit::Desc;
  using Ports = PortImage<Top, Image>;

  // The records of the two narrow streams, taken straight from their ports.
  static constexpr auto kVisitFields = Desc::kVisitFields;
  static_assert(fx::recordBits(kVisitFields) <= 64 && kVisitFields.size() == 2, "a visit is {ray_id, element}");
  static constexpr int kVisitRayLsb = fieldLsb(kVisitFields, 0);
  static constexpr int kVisitIdLsb = fieldLsb(kVisitFields, 1);
  static constexpr int kVisitIdBits = kVisitFields[1].width;
  static_assert(kVisitFields[0].width == 32 && kVisitIdBits <= 32 && kVisitRayLsb + 32 == fx::recordBits(kVisitFields));
  static constexpr uint64_t kVisitIdMask = (uint64_t(1) << kVisitIdBits) - 1;
  static constexpr size_t kResWords = size_t(fx::wireWords(fx::recordBits(Desc::kResFields)));
  static constexpr size_t kVisitWords = size_t(fx::wireWords(fx::recordBits(kVisitFields)));
  static constexpr size_t kFirstVisits = 16;  // a ray's visit list starts this long
  static constexpr size_t kWalkWords = size_t(fx::wireWords(fx::kWalkBitsOf<Desc>));
  static size_t visitRay(uint64_t visit) { return uint32_t(visit >> kVisitRayLsb); }  // {ray_id, element}

 public:
  UnitRun(Clocked& unit, int index, const Ports& ports, ChipRays& shared, const TraversalRunOptions& options,
          std::vector<sc::TraversalCycle>* portTrace)
      : unit_(unit), top_(unit.top()), index_(index), ports_(ports), shared_(shared), options_(options),
        stim_(options, index), portTrace_(index == 0 ? portTrace : nullptr) {
    static_assert(portWords<std::remove_reference_t<decltype(std::get<5>(Unit::nodePort(top_)))>>() ==
                      Ports::kGroupWords,
                  "the node response port does not carry kGroup nodes of the descriptor: rebuild rt_pkg");
    static_assert(portWords<std::remove_reference_t<decltype(top_.res_data_o)>>() >= kResWords,
                  "res_data_o does not match the unit's result record: rebuild rt_pkg");
  }

  // Whether the clocked model can set walks aside (the treelet schedule).
  static constexpr bool kSuspends = requires(Top& t) { t.cfg_suspend_i; };

  // The run's slots and the unit's configuration port.
  void configure() {
    top_.cfg_slots_i = options_.raysInFlight == 0 ? Unit::kMaxSlots : options_.raysInFlight;
    trav_detail::configure(top_, ports_.image);
    if constexpr (kSuspends) {
      top_.cfg_suspend_i = options_.treelets;
      top_.cfg_block_shift_i = fx::treeletBlockShift(ports_.image);
    }
  }

  // The walks this unit set aside in the cycle just run (taken at its end).
  std::vector<SuspendedWalk>& suspended() { return suspended_; }

  // One cycle of the chip: the memory's responses and this unit's offer, the
  // inputs settled, the handshakes, the rising edge. True if the unit made
  // progress (a ray accepted, a test, a visit or a result).
  bool cycle(mem::MemorySystem& memory) {
    unit_.select();
    // A visit on offer (a registered output) goes to its ray's trace below: the
    // trace is a cache miss, fetched while the inputs settle.
    if (top_.visit_valid_o) {
      const size_t k = visitRay(uint64_t(portValue(top_.visit_data_o)));
      if (k < shared_.traces.size()) __builtin_prefetch(&shared_.traces[k]);
    }
    const uint64_t now = memory.cycle();
    offerRay(now);
    const bool resReady = !stim_.stallRes();
    const bool visitReady = !stim_.stallVisit();
    top_.res_ready_i = resReady;
    top_.visit_ready_i = visitReady;
    driveResponses(memory);
    unit_.settle();
    if (portTrace_ && started_) recordPorts(now, resReady, visitReady);
    // Handshakes of this cycle, read with the inputs settled (perf_isect_fire_o
    // is combinational in tri_rsp_valid_i).
    const bool rayFire = offering_ && top_.ray_ready_o;
    bool progress = takeRequests(memory) || rayFire;
    if (top_.visit_valid_o && visitReady) progress = takeVisit(now);
    if (top_.res_valid_o && resReady) progress = takeResult(now);
    if (accepted_ > results_) ++busyCycles_;
    unit_.tick();
    if (rayFire) {
      offering_ = false;
      shared_.owner[offeredRay_] = index_;
      shared_.dispatcher.taken(index_);
      ++accepted_;
    }
    return progress;
  }

  // No ray of this unit in flight, nothing on its visit port.
  bool drained() const { return accepted_ == results_ && !offering_ && !top_.visit_valid_o; }
  uint64_t results() const { return results_; }
  uint64_t accepted() const { return accepted_; }
  bool started() const { return started_; }
  uint64_t firstCycle() const { return firstCycle_; }
  uint64_t lastCycle() const { return lastCycle_; }
  uint64_t busyCycles() const { return busyCycles_; }
  const TraversalRunStats& stats() const { return stats_; }

 private:
  [[noreturn]] static void fail(const std::string& what) {
    throw std::runtime_error(fmt::format("{}: {}", Clocked::kModel, what));
  }

  // Producer: the next ray the dispatcher handed this unit, unless idling; an
  // offer holds until taken. The ray crosses the port with its index in the
  // run as its id.
  void offerRay(uint64_t now) {
    if (!offering_ && shared_.dispatcher.holds(index_, now) && !stim_.idle()) {
      offeredRay_ = shared_.dispatcher.next(index_);
      fx::QRay wireRay = shared_.rays[shared_.rayOf(offeredRay_)];
      wireRay.id = uint32_t(offeredRay_);
      fx::packWire(wireRay, rayWire_);
      writePort(top_.ray_data_i, rayWire_.data(), fx::kIsectRayWords);
      if constexpr (kSuspends) {
        const ChipRays::Resumed* resumed = shared_.resumedWalk(offeredRay_);
        top_.ray_resume_i = resumed != nullptr;
        if (resumed) writePort(top_.ray_walk_i, resumed->walk.data(), resumed->walk.size());
      }
      offering_ = true;
      if (!started_) {
        started_ = true;
        firstCycle_ = now;
      }
    }
    top_.ray_valid_i = offering_;
  }

  // The memory responses of this cycle on the three ports, and their readiness.
  void driveResponses(mem::MemorySystem& memory) {
    auto [reqValid, reqAddr, reqTag, reqReady, rspValid, rspData, rspTag] = Unit::nodePort(top_);
    const Image& image = ports_.image;
    uint32_t addr = 0, tag = 0;
    rspValid = response(memory, mem::Port::Node, addr, tag);
    if (rspValid) {
      if (uint64_t(addr) + Desc::kGroup > ports_.nodes.size()) {
        fail(fmt::format("{} read at {} outside the {} ({} entries)", Desc::kNames.nodeRead, addr,
                         Desc::kNames.nodeTable, ports_.nodes.size()));
      }
      writePort(rspData, &ports_.nodeWire[size_t(addr) * Ports::kNodeWords], Ports::kGroupWords);
      rspTag = tag;
    }
    top_.idx_rsp_valid_i = response(memory, mem::Port::Index, addr, tag);
    if (top_.idx_rsp_valid_i) {
      if (addr >= image.indices.size()) {
        fail(fmt::format("index list read at {} outside the image ({} entries)", addr, image.indices.size()));
      }
      top_.idx_rsp_data_i = image.indices[addr];
      top_.idx_rsp_tag_i = tag;
    }
    // The primitive port: a triangle's record, or a quadric's (the request's kind bit).
    const bool primitive = response(memory, mem::Port::Triangle, addr, tag);
    const bool quadric = primitive && fx::isQuadricEntry(addr);
    top_.tri_rsp_valid_i = primitive && !quadric;
    top_.quadric_rsp_valid_i = quadric;
    if (quadric) {
      ++stats_.quadricTests;  // each quadric read is one test of rt_quadric
      const uint32_t place = fx::entryPlace(addr);
      if (place >= image.quadrics.size()) {
        fail(fmt::format("quadric table read at {} outside the image ({} entries)", place, image.quadrics.size()));
      }
      writePort(top_.quadric_rsp_data_i, &ports_.quadricWire[size_t(place) * Ports::kQuadricWords],
                Ports::kQuadricWords);
      top_.quadric_rsp_tag_i = tag;
    } else if (primitive) {
      if (addr >= image.triangles.size()) {
        fail(fmt::format("triangle table read at {} outside the image ({} entries)", addr, image.triangles.size()));
      }
      writePort(top_.tri_rsp_data_i, &ports_.triWire[size_t(addr) * Ports::kTriWords], Ports::kTriWords);
      top_.tri_rsp_tag_i = tag;
    }
    reqReady = memory.ready(index_, mem::Port::Node);
    top_.idx_req_ready_i = memory.ready(index_, mem::Port::Index);
    top_.tri_req_ready_i = memory.ready(index_, mem::Port::Triangle);
  }

  // One port's request of this cycle: to the memory if it is ready.
  template <class Valid, class Ready>
  bool request(mem::MemorySystem& memory, mem::Port port, const Valid& valid, const Ready& ready, uint32_t addr,
               uint32_t tag) {
    if (!valid) return false;
    if (!ready) {
      memory.blocked(index_, port);
      return false;
    }
    memory.request(index_, port, addr, tag);
    ++pending_[size_t(port)];
    return true;
  }

  // The port's response of this cycle, asked of the memory only while one of
  // its reads is outstanding (most cycles, some port has none).
  bool response(mem::MemorySystem& memory, mem::Port port, uint32_t& addr, uint32_t& tag) {
    uint64_t& pending = pending_[size_t(port)];
    if (pending == 0 || !memory.response(index_, port, addr, tag)) return false;
    --pending;
    return true;
  }

  // The memory requests, the pipeline's test and the step-ready count of this
  // cycle; true if a test entered the pipeline.
  bool takeRequests(mem::MemorySystem& memory) {
    auto [reqValid, reqAddr, reqTag, reqReady, rspValid, rspData, rspTag] = Unit::nodePort(top_);
    stats_.nodeReads += request(memory, mem::Port::Node, reqValid, reqReady, reqAddr, reqTag);
    stats_.indexReads += request(memory, mem::Port::Index, top_.idx_req_valid_o, top_.idx_req_ready_i,
                                 top_.idx_req_addr_o, top_.idx_req_tag_o);
    // A primitive read names its table by the entry's kind bit (mem::AddressMap::span).
    const uint32_t primitive = fx::primitiveEntry(uint32_t(top_.tri_req_addr_o), top_.tri_req_quadric_o);
    stats_.triangleReads += request(memory, mem::Port::Triangle, top_.tri_req_valid_o, top_.tri_req_ready_i,
                                    primitive, top_.tri_req_tag_o);
    if (started_ && top_.perf_step_ready_o) ++stats_.stepReadyCycles;
    if (!top_.perf_isect_fire_o) return false;
    ++stats_.isectTests;
    ++stats_.isectBusyCycles;
    return true;
  }

  // The unit's port activity in this cycle, as the SystemC testbench records
  // it (sc::TraversalCycle, rt_trav_stream): cycles counted from the first
  // ray offered; addresses, tags and records only while valid.
  void recordPorts(uint64_t now, bool resReady, bool visitReady) {
    auto [reqValid, reqAddr, reqTag, reqReady, rspValid, rspData, rspTag] = Unit::nodePort(top_);
    sc::TraversalCycle c;
    c.cycle = now - firstCycle_;
    c.rayValid = offering_;
    c.rayReady = top_.ray_ready_o;
    c.resValid = top_.res_valid_o;
    c.resReady = resReady;
    c.visitValid = top_.visit_valid_o;
    c.visitReady = visitReady;
    const auto request = [](bool valid, uint32_t addr, uint32_t tag, bool& v, uint32_t& a, uint32_t& t) {
      v = valid;
      if (valid) a = addr, t = tag;
    };
    request(reqValid, reqAddr, reqTag, c.nodeReq, c.nodeAddr, c.nodeTag);
    request(top_.idx_req_valid_o, top_.idx_req_addr_o, top_.idx_req_tag_o, c.idxReq, c.idxAddr, c.idxTag);
    request(top_.tri_req_valid_o, top_.tri_req_addr_o, top_.tri_req_tag_o, c.triReq, c.triAddr, c.triTag);
    c.triQuadric = top_.tri_req_valid_o && top_.tri_req_quadric_o;
    c.perfIsectFire = top_.perf_isect_fire_o;
    c.perfStepReady = top_.perf_step_ready_o;
    if (c.resValid) {
      c.resData.resize(kResWords);
      readPort(top_.res_data_o, c.resData.data(), kResWords);
    }
    if (c.visitValid) {
      c.visitData.resize(kVisitWords);
      readPort(top_.visit_data_o, c.visitData.data(), kVisitWords);
    }
    portTrace_->push_back(std::move(c));
  }

  // The ray of a visit or result record: one this unit took (visits may
  // trail the ray's result; a second result is an error).
  size_t ownRay(uint64_t id, const char* what, bool result) const {
    const size_t k = size_t(id);
    if (k >= shared_.walks() || shared_.owner[k] != index_ || (result && shared_.finished[k])) {
      fail(fmt::format("unit {}: a {} for ray {} that is not in flight in it", index_, what, k));
    }
    return k;
  }

  bool takeVisit(uint64_t now) {
    const uint64_t visit = top_.visit_data_o;  // {ray_id, element}
    const size_t k = ownRay(visitRay(visit), "visit record", false);
    std::vector<uint32_t>& visits = shared_.visitsOf(k);
    if (visits.empty()) visits.reserve(kFirstVisits);  // one allocation for most walks, not five
    visits.push_back(uint32_t((visit >> kVisitIdLsb) & kVisitIdMask));
    ++stats_.steps;
    lastCycle_ = now;
    return true;
  }

  bool takeResult(uint64_t now) {
    readPort(top_.res_data_o, resWire_.data(), kResWords);
    res_ = fx::wire_bits::unpackFixed<Desc::kResFieldList>(resWire_);
    const size_t k = ownRay(uint64_t(res_[0]), "result", true);
    shared_.finished[k] = 1;
    // A walk's counts add to its ray's walks before it (none for its first).
    const size_t ray = shared_.rayOf(k);
    fx::TraversalTrace part;
    shared_.resultElements[k] = fx::takeTraversalResult(res_, shared_.rays[ray].id, part);
    fx::TraversalTrace& trace = shared_.traces[ray];
    trace.tests += part.tests;
    trace.quadricTests += part.quadricTests;
    trace.hit = part.hit;
    if constexpr (kSuspends) {
      if (top_.res_suspended_o) {  // not over: its record to the ray queues (its hit so far is in it)
        shared_.traces[ray].hit.reset();
        std::vector<uint32_t> record(kWalkWords);
        readPort(top_.res_walk_o, record.data(), kWalkWords);
        suspended_.push_back(SuspendedWalk{k, std::move(record)});
      }
    }
    ++results_;
    lastCycle_ = now;
    return true;
  }

  Clocked& unit_;
  Top& top_;
  int index_;
  const Ports& ports_;
  ChipRays& shared_;
  const TraversalRunOptions& options_;
  TraversalStimulus stim_;
  std::array<uint64_t, mem::kPorts> pending_{};  // reads requested and not yet answered, per port
  std::vector<sc::TraversalCycle>* portTrace_;  // unit 0's, when asked for
  std::array<uint32_t, kResWords> resWire_{};
  std::array<fx::u128, fx::valueCount(Desc::kResFields)> res_{};
  fx::RayWire rayWire_{};
  TraversalRunStats stats_;
  std::vector<SuspendedWalk> suspended_;
  size_t offeredRay_ = 0;
  uint64_t accepted_ = 0, results_ = 0, busyCycles_ = 0;
  bool offering_ = false, started_ = false;
  uint64_t firstCycle_ = 0, lastCycle_ = 0;
};

// A chip's run: its units clocked in lockstep with the memory system, one
// cycle at a time, until every ray has its result and the memory is quiet.
// With more than one host thread, each thread clocks its share of the units
// (unit u on thread u % threads) and a barrier ends each cycle; the memory
// system's tick and the dispatcher run alone in the barrier's completion, in
// unit order, so a run is the same whatever the threads.
template <class Clocked, class Image>
class ChipRun {
  using Desc = typename TraversalTop<typename Clocked::top_type>::Desc;

 public:
  ChipRun(std::deque<UnitRun<Clocked, Image>>& units, mem::MemorySystem& memory, ChipRays& shared, int threads,
          const Image& image)
      : units_(units), memory_(memory), shared_(shared), threads_(threads), image_(image),
        progress_(units.size(), 0) {}

  void run() {
    shared_.dispatcher.refill();
    // The path's memory system counts on from its earlier runs.
    lastProgress_ = memory_.cycle();
    if (threads_ <= 1) {
      while (!stop_) {
        for (size_t u = 0; u < units_.size(); ++u) progress_[u] = units_[u].cycle(memory_);
        endCycle();
      }
      return;
    }
    CycleBarrier sync(threads_);
    std::vector<std::exception_ptr> errors(static_cast<size_t>(threads_));
    const auto work = [&](int t) {
      while (true) {
        if (!errors[size_t(t)]) {
          try {
            for (size_t u = size_t(t); u < units_.size(); u += size_t(threads_)) progress_[u] = units_[u].cycle(memory_);
          } catch (...) {
            errors[size_t(t)] = std::current_exception();
            failed_.store(true);
          }
        }
        sync.arriveAndWait([this] { endCycle(); });
        if (stop_) return;
      }
    };
    std::vector<std::jthread> pool;
    for (int t = 1; t < threads_; ++t) pool.emplace_back(work, t);
    work(0);
    pool.clear();
    for (const std::exception_ptr& e : errors) {
      if (e) std::rethrow_exception(e);
    }
  }

 private:
  // The end of every cycle, alone: the memory's work, the dispatcher, the
  // end of the run, the watchdog.
  void endCycle() {
    // The walks set aside in this cycle, unit by unit, into the ray queues.
    if constexpr (fx::SuspendsWalks<Desc>) {
      if (mem::RayQueues* queues = shared_.dispatcher.queues()) {
        for (auto& unit : units_) {
          for (SuspendedWalk& w : unit.suspended()) {
            const auto values = fx::wire_bits::unpackFixed<Desc::kWalkFieldList>(w.record);
            const auto at = Desc::suspended(image_, values);
            queues->suspend(shared_.addResumed(shared_.rayOf(w.walk), std::move(w.record)), at.block, at.bits);
          }
          unit.suspended().clear();
        }
        queues->endCycle();
      }
    }
    memory_.tick();
    shared_.dispatcher.refill();
    bool progress = false;
    bool drained = true;
    uint64_t results = 0;
    for (size_t u = 0; u < units_.size(); ++u) {
      progress |= progress_[u] != 0;
      drained &= units_[u].drained();
      results += units_[u].results();
    }
    if (progress) lastProgress_ = memory_.cycle();
    const bool queued = shared_.dispatcher.queues() && !shared_.dispatcher.queues()->empty();
    if (failed_.load()) {
      stop_ = true;
    } else if (results == shared_.walks() && !queued && drained && memory_.idle()) {  // (the memory's scan last: it is long)
      stop_ = true;
    } else if (memory_.cycle() - lastProgress_ > kTraversalWatchdogCycles) {
      stop_ = true;
      watchdog_ = fmt::format("{}: no progress for {} cycles ({} of {} rays have results)", Clocked::kModel,
                              kTraversalWatchdogCycles,
                              results, shared_.rays.size());
    }
  }

 public:
  const std::string& watchdog() const { return watchdog_; }

 private:
  std::deque<UnitRun<Clocked, Image>>& units_;
  mem::MemorySystem& memory_;
  ChipRays& shared_;
  int threads_;
  const Image& image_;
  std::vector<uint8_t> progress_;
  bool stop_ = false;
  std::atomic<bool> failed_{false};
  uint64_t lastProgress_ = 0;
  std::string watchdog_;
};

}  // namespace trav_detail

// A run of a chip of `options.units` units of one clocked model on `rays`:
// the units are made by `make()` as a run first needs them and kept in
// `pool` across runs; each is reset, configured, clocked with the memory
// system until every ray has its result, and left idle. `portTrace`
// (optional) gets unit 0's port activity per cycle. The caller has checked
// the options (checkTraversalOptions).
template <class Clocked, class Image, class Make>
TraversalRunStats runTraversalChip(std::vector<std::unique_ptr<Clocked>>& pool, Make make, const Image& image,
                                   std::span<const fx::QRay> rays, std::vector<fx::TraversalTrace>& traces,
                                   const TraversalRunOptions& options,
                                   std::vector<sc::TraversalCycle>* portTrace = nullptr) {
  using Top = typename Clocked::top_type;
  using Desc = typename TraversalTop<Top>::Desc;
  Desc::checkImage(image, rays);
  traces.assign(rays.size(), fx::TraversalTrace{});
  if (rays.empty()) return TraversalRunStats{};

  const int units = options.units;
  while (int(pool.size()) < units) {
    pool.push_back(make());
  }
  std::unique_ptr<mem::MemorySystem> own;
  mem::MemorySystem& memory = memoryFor<Desc>(options, image, own);
  const trav_detail::PortImage<Top, Image> ports(image);
  trav_detail::ChipRays shared(rays, traces, units, options.dispatchBatch);
  if (options.treelets) {
    if constexpr (!trav_detail::UnitRun<Clocked, Image>::kSuspends) {
      throw InputError(fmt::format("--schedule treelet: the {} model of the {} unit cannot set walks aside (no "
                                   "suspend and resume ports); the treelet schedule runs on the golden, systemc and "
                                   "rtl models of the BVH and the octree",
                                   Clocked::kModel, Desc::kNames.unit));
    }
    shared.dispatcher.useQueues(std::make_unique<mem::RayQueues>(options.queues, rays.size(), memory));
  }
  std::deque<trav_detail::UnitRun<Clocked, Image>> runs;  // (not movable: a deque grows in place)
  for (int u = 0; u < units; ++u) {
    Clocked& unit = *pool[size_t(u)];
    runs.emplace_back(unit, u, ports, shared, options, portTrace);
    unit.reset(trav_detail::idleInputs<Top>);
    runs.back().configure();
    unit.settle();
  }
  // The waveform is unit 0's.
  pool.front()->openWave(nextWaveFile(options.stream.wavePath));
  const int threads = options.hostThreads > 0
                          ? std::min(options.hostThreads, units)
                          : std::min(units, std::max(1, int(std::thread::hardware_concurrency())));
  trav_detail::ChipRun<Clocked, Image> chip(runs, memory, shared, threads, image);
  try {
    chip.run();
  } catch (...) {
    pool.front()->closeWave();
    throw;
  }
  for (int u = 0; u < units; ++u) {
    Clocked& unit = *pool[size_t(u)];
    trav_detail::idleInputs(unit.top());
    runs[size_t(u)].configure();
    unit.settle();
  }
  pool.front()->closeWave();
  if (!chip.watchdog().empty()) throw std::runtime_error(chip.watchdog());

  TraversalRunStats stats;
  uint64_t first = UINT64_MAX, last = 0;
  for (const auto& run : runs) {
    stats += run.stats();
    stats.unitRays.push_back(run.accepted());
    stats.unitBusyCycles.push_back(run.busyCycles());
    if (run.started()) first = std::min(first, run.firstCycle());
    last = std::max(last, run.lastCycle());
  }
  stats.rays = rays.size();
  stats.cycles = last - first + 1;
  stats.memory = memory.stats();
  if (const mem::RayQueues* queues = shared.dispatcher.queues()) stats.queues = queues->stats();
  for (size_t k = 0; k < shared.walks(); ++k) {
    const size_t visits = shared.visitsOf(k).size();
    if (shared.resultElements[k] != visits) {
      throw std::runtime_error(fmt::format("{}: ray {} reports {} {} but {} visit records came out{}", Clocked::kModel,
                                           shared.rayOf(k), shared.resultElements[k], Desc::kNames.elements, visits,
                                           k < rays.size() ? "" : " (a resumed walk)"));
    }
  }
  // A ray's resumed walks' visits follow its first walk's, in the order the walks were resumed.
  for (trav_detail::ChipRays::Resumed& walk : shared.resumed) {
    std::vector<uint32_t>& into = traces[walk.ray].visits;
    into.insert(into.end(), walk.visits.begin(), walk.visits.end());
  }
  return stats;
}

}  // namespace lancer
