#pragma once

// The members of VerilatorTraversalDevice<Top, Image>. Included by the .cpp of
// each unit's device only, after its VerilatedTraversalUnit<Top>
// specialization and the Verilated header, followed by
//   template class VerilatorTraversalDevice<Top, Image>;
//
// LANCER_VERILATED_TRAVERSAL_UNIT (below) writes the specialization
// VerilatedTraversalUnit<Top>, which defines (all static, inline) only what
// names the Verilated model's own members:
//   Desc               the unit's descriptor (golden/unit.h): names, records,
//                      node packing, configuration, image checks
//   kMaxSlots          RaysInFlight, from the unit's compile definition
//   nodePort(top)      std::tie of the node port: req valid, addr, tag,
//                      req ready, rsp valid, data, tag
//   configPort(top)    its configuration port besides cfg_slots_i

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/verilated_port.h"
#include "driver/verilated_unit.h"
#include "driver/verilator_traversal_device.h"

namespace lancer {

namespace trav_detail {

// The unit's configuration port for `image` (an empty Image at reset).
template <class Top, class Image>
void configure(Top& top, const Image& image) {
  using Desc = typename VerilatedTraversalUnit<Top>::Desc;
  std::array<uint32_t, size_t(fx::wireWords(fx::kCfgBitsOf<Desc>))> wire{};
  fx::packConfig<Desc>(image, wire);
  auto& port = VerilatedTraversalUnit<Top>::configPort(top);
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
  using Unit = VerilatedTraversalUnit<Top>;
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
  top.cfg_slots_i = Unit::kMaxSlots;
  configure(top, typename Unit::Desc::Image{});
}

}  // namespace trav_detail

template <class Top, class Image>
VerilatorTraversalDevice<Top, Image>::VerilatorTraversalDevice()
    : unit_(std::make_unique<VerilatedUnit<Top>>(VerilatedTraversalUnit<Top>::Desc::kNames.module)) {
  unit_->reset(trav_detail::idleInputs<Top>);
}

template <class Top, class Image>
VerilatorTraversalDevice<Top, Image>::~VerilatorTraversalDevice() = default;

template <class Top, class Image>
int VerilatorTraversalDevice<Top, Image>::maxRaysInFlight() const {
  return VerilatedTraversalUnit<Top>::kMaxSlots;
}

namespace trav_detail {

// One run of a Verilated traversal unit, cycle by cycle: the image as its
// ports carry it (packed once; nothing is allocated per cycle), the seeded
// stimulus, and what came out. Every member is inlined into the loop.
template <class Top, class Image>
class TraversalRun {
  using Unit = VerilatedTraversalUnit<Top>;
  using Desc = typename Unit::Desc;

  // The records of the two narrow streams, taken straight from their ports.
  static constexpr auto kVisitFields = Desc::kVisitFields;
  static_assert(fx::recordBits(kVisitFields) <= 64 && kVisitFields.size() == 2, "a visit is {ray_id, element}");
  static constexpr int kVisitRayLsb = fieldLsb(kVisitFields, 0);
  static constexpr int kVisitIdLsb = fieldLsb(kVisitFields, 1);
  static constexpr int kVisitIdBits = kVisitFields[1].width;
  static_assert(kVisitFields[0].width == 32 && kVisitIdBits <= 32 && kVisitRayLsb + 32 == fx::recordBits(kVisitFields));
  static constexpr uint64_t kVisitIdMask = (uint64_t(1) << kVisitIdBits) - 1;
  static constexpr size_t kResWords = size_t(fx::wireWords(fx::recordBits(Desc::kResFields)));
  static constexpr size_t kTriWords = fx::kIsectTriWords;
  static constexpr size_t kNodeWords = size_t(fx::wireWords(fx::kNodeBitsOf<Desc>));
  static constexpr size_t kGroupWords = Desc::kGroup * kNodeWords;

 public:
  TraversalRun(VerilatedUnit<Top>& unit, const Image& image, std::span<const fx::QRay> rays,
               std::vector<fx::TraversalTrace>& traces, const TraversalRunOptions& options)
      : unit_(unit), top_(unit.top()), image_(image), nodes_(Desc::nodes(image)), rays_(rays), traces_(traces),
        options_(options), stim_(options), finished_(rays.size(), 0), resultElements_(rays.size(), 0) {
    static_assert(portWords<std::remove_reference_t<decltype(std::get<5>(Unit::nodePort(top_)))>>() == kGroupWords,
                  "the node response port does not carry kGroup nodes of the descriptor: rebuild rt_pkg");
    static_assert(portWords<std::remove_reference_t<decltype(top_.res_data_o)>>() >= kResWords,
                  "res_data_o does not match the unit's result record: rebuild rt_pkg");
    nodeWire_.resize(nodes_.size() * kNodeWords);
    for (size_t i = 0; i < nodes_.size(); ++i) {
      fx::packNode<Desc>(nodes_[i], std::span<uint32_t>(nodeWire_).subspan(kNodeWords * i, kNodeWords));
    }
    triWire_.resize(image.triangles.size() * kTriWords);
    for (size_t i = 0; i < image.triangles.size(); ++i) {
      fx::packWire(image.triangles[i], std::span<uint32_t>(triWire_).subspan(i * kTriWords, kTriWords));
    }
    stats_.rays = rays.size();
  }

  // The run's slots and the unit's configuration port.
  void configure() {
    top_.cfg_slots_i = options_.raysInFlight == 0 ? Unit::kMaxSlots : options_.raysInFlight;
    trav_detail::configure(top_, image_);
  }

  // Clocks the unit until every ray has its result and the ports are quiet.
  TraversalRunStats run() {
    lastProgress_ = unit_.cycle();
    while (results_ < rays_.size() || !stim_.memoryIdle() || top_.visit_valid_o) {
      const uint64_t cycle = unit_.cycle();
      offerRay(cycle);
      const bool resReady = !stim_.stallRes();
      const bool visitReady = !stim_.stallVisit();
      top_.res_ready_i = resReady;
      top_.visit_ready_i = visitReady;
      driveResponses(cycle);
      unit_.settle();
      // Handshakes of this cycle, read with the inputs settled (perf_isect_fire_o
      // is combinational in tri_rsp_valid_i). The memory ports are always ready.
      const bool rayFire = offering_ && top_.ray_ready_o;
      bool progress = takeRequests(cycle) || rayFire;
      if (top_.visit_valid_o && visitReady) progress = takeVisit(cycle);
      if (top_.res_valid_o && resReady) progress = takeResult(cycle);
      unit_.tick();
      if (rayFire) {
        offering_ = false;
        ++offered_;
      }
      watchdog(progress);
    }
    return stats_;
  }

  // Each ray's result names as many elements as its visit records.
  void checkResultCounts() const {
    for (size_t k = 0; k < rays_.size(); ++k) {
      if (resultElements_[k] != traces_[k].visits.size()) {
        fail(fmt::format("ray {} reports {} {} but {} visit records came out", k, resultElements_[k],
                         Desc::kNames.elements, traces_[k].visits.size()));
      }
    }
  }

 private:
  [[noreturn]] static void fail(const std::string& what) { throw std::runtime_error("rtl: " + what); }

  // Producer: the next ray, unless idling; an offer holds until taken.
  void offerRay(uint64_t cycle) {
    if (!offering_ && offered_ < rays_.size() && !stim_.idle()) {
      fx::QRay wireRay = rays_[offered_];
      wireRay.id = uint32_t(offered_);
      fx::packWire(wireRay, rayWire_);
      writePort(top_.ray_data_i, rayWire_.data(), fx::kIsectRayWords);
      offering_ = true;
      if (!started_) {
        started_ = true;
        firstCycle_ = cycle;
      }
    }
    top_.ray_valid_i = offering_;
  }

  // The memory responses due in this cycle, on the three ports.
  void driveResponses(uint64_t cycle) {
    auto [reqValid, reqAddr, reqTag, reqReady, rspValid, rspData, rspTag] = Unit::nodePort(top_);
    uint32_t addr = 0, tag = 0;
    rspValid = stim_.nodePort.respond(cycle, addr, tag);
    if (rspValid) {
      if (uint64_t(addr) + Desc::kGroup > nodes_.size()) {
        fail(fmt::format("{} read at {} outside the {} ({} entries)", Desc::kNames.nodeRead, addr,
                         Desc::kNames.nodeTable, nodes_.size()));
      }
      writePort(rspData, &nodeWire_[size_t(addr) * kNodeWords], kGroupWords);
      rspTag = tag;
    }
    top_.idx_rsp_valid_i = stim_.idxPort.respond(cycle, addr, tag);
    if (top_.idx_rsp_valid_i) {
      if (addr >= image_.indices.size()) {
        fail(fmt::format("index list read at {} outside the image ({} entries)", addr, image_.indices.size()));
      }
      top_.idx_rsp_data_i = image_.indices[addr];
      top_.idx_rsp_tag_i = tag;
    }
    top_.tri_rsp_valid_i = stim_.triPort.respond(cycle, addr, tag);
    if (top_.tri_rsp_valid_i) {
      if (addr >= image_.triangles.size()) {
        fail(fmt::format("triangle table read at {} outside the image ({} entries)", addr, image_.triangles.size()));
      }
      writePort(top_.tri_rsp_data_i, &triWire_[size_t(addr) * kTriWords], kTriWords);
      top_.tri_rsp_tag_i = tag;
    }
  }

  // The memory requests, the pipeline's test and the step-ready count of this
  // cycle; true if a test entered the pipeline.
  bool takeRequests(uint64_t cycle) {
    auto [reqValid, reqAddr, reqTag, reqReady, rspValid, rspData, rspTag] = Unit::nodePort(top_);
    if (reqValid) {
      stim_.nodePort.request(cycle, reqAddr, reqTag);
      ++stats_.nodeReads;
    }
    if (top_.idx_req_valid_o) {
      stim_.idxPort.request(cycle, top_.idx_req_addr_o, top_.idx_req_tag_o);
      ++stats_.indexReads;
    }
    if (top_.tri_req_valid_o) {
      stim_.triPort.request(cycle, top_.tri_req_addr_o, top_.tri_req_tag_o);
      ++stats_.triangleReads;
    }
    if (started_ && top_.perf_step_ready_o) ++stats_.stepReadyCycles;
    if (!top_.perf_isect_fire_o) return false;
    ++stats_.isectTests;
    ++stats_.isectBusyCycles;
    return true;
  }

  bool takeVisit(uint64_t cycle) {
    const uint64_t visit = top_.visit_data_o;  // {ray_id, element}
    const size_t k = size_t(uint32_t(visit >> kVisitRayLsb));
    if (k >= offered_) fail(fmt::format("a visit record for ray {} that was never accepted", k));
    traces_[k].visits.push_back(uint32_t((visit >> kVisitIdLsb) & kVisitIdMask));
    ++stats_.steps;
    stats_.cycles = cycle - firstCycle_ + 1;
    return true;
  }

  bool takeResult(uint64_t cycle) {
    readPort(top_.res_data_o, resWire_.data(), kResWords);
    fx::unpackFields(Desc::kResFields, resWire_, res_);
    const size_t k = size_t(res_[0]);
    if (k >= offered_ || finished_[k]) fail(fmt::format("a result for ray {} that is not in flight", k));
    finished_[k] = 1;
    resultElements_[k] = fx::takeTraversalResult(res_, rays_[k].id, traces_[k]);
    ++results_;
    stats_.cycles = cycle - firstCycle_ + 1;
    return true;
  }

  void watchdog(bool progress) {
    if (progress) lastProgress_ = unit_.cycle();
    if (unit_.cycle() - lastProgress_ > kTraversalWatchdogCycles) {
      fail(fmt::format("no progress for {} cycles ({} of {} rays accepted, {} results)", kTraversalWatchdogCycles,
                       offered_, rays_.size(), results_));
    }
  }

  VerilatedUnit<Top>& unit_;
  Top& top_;
  const Image& image_;
  const std::remove_cvref_t<decltype(Desc::nodes(std::declval<const Image&>()))>& nodes_;
  std::span<const fx::QRay> rays_;
  std::vector<fx::TraversalTrace>& traces_;
  const TraversalRunOptions& options_;
  TraversalStimulus stim_;
  std::vector<uint32_t> nodeWire_, triWire_;
  std::vector<uint8_t> finished_;
  std::vector<uint32_t> resultElements_;
  std::array<uint32_t, kResWords> resWire_{};
  std::array<fx::u128, fx::valueCount(Desc::kResFields)> res_{};
  fx::RayWire rayWire_{};
  TraversalRunStats stats_;
  size_t offered_ = 0, results_ = 0;
  bool offering_ = false, started_ = false;
  uint64_t firstCycle_ = 0, lastProgress_ = 0;
};

}  // namespace trav_detail

template <class Top, class Image>
TraversalRunStats VerilatorTraversalDevice<Top, Image>::run(const Image& image, std::span<const fx::QRay> rays,
                                                            std::vector<fx::TraversalTrace>& traces,
                                                            const TraversalRunOptions& options) {
  using Desc = typename VerilatedTraversalUnit<Top>::Desc;
  checkTraversalOptions(options, maxRaysInFlight(), Desc::kNames.unit, Desc::kNames.slotsOption);
  Desc::checkImage(image, rays);
  traces.assign(rays.size(), fx::TraversalTrace{});
  if (rays.empty()) return TraversalRunStats{};

  VerilatedUnit<Top>& unit = *unit_;
  trav_detail::TraversalRun<Top, Image> run(unit, image, rays, traces, options);
  unit.reset(trav_detail::idleInputs<Top>);
  run.configure();
  unit.settle();
  unit.openWave(options.stream.wavePath);
  TraversalRunStats stats;
  try {
    stats = run.run();
  } catch (...) {
    unit.closeWave();
    throw;
  }
  trav_detail::idleInputs(unit.top());
  run.configure();
  unit.settle();
  unit.closeWave();
  run.checkResultCounts();
  return stats;
}

}  // namespace lancer

// A unit's Verilated device, in its verilator_<unit>_device.cpp: the traits of
// the Verilated model `Top` for the descriptor `Descriptor` (its node port's
// members start with `Prefix`, its configuration port is `CfgPort`, it has
// `Slots` ray slots), the device's explicit instantiation and its factory.
#define LANCER_VERILATED_TRAVERSAL_UNIT(Top, Descriptor, Slots, Prefix, CfgPort)                                 \
  namespace lancer {                                                                                             \
  template <>                                                                                                    \
  struct VerilatedTraversalUnit<Top> {                                                                           \
    using Desc = Descriptor;                                                                                     \
    static constexpr int kMaxSlots = Slots;                                                                      \
    static auto nodePort(Top& t) {                                                                               \
      return std::tie(t.Prefix##_req_valid_o, t.Prefix##_req_addr_o, t.Prefix##_req_tag_o, t.Prefix##_req_ready_i, \
                      t.Prefix##_rsp_valid_i, t.Prefix##_rsp_data_i, t.Prefix##_rsp_tag_i);                      \
    }                                                                                                            \
    static auto& configPort(Top& t) { return t.CfgPort; }                                                        \
  };                                                                                                             \
  template class VerilatorTraversalDevice<Top, Descriptor::Image>;                                               \
  template <>                                                                                                    \
  std::unique_ptr<DeviceOf<Descriptor>> makeVerilatorDevice<Descriptor>() {                                      \
    return std::make_unique<VerilatorTraversalDevice<Top, Descriptor::Image>>();                                 \
  }                                                                                                              \
  }  // namespace lancer
