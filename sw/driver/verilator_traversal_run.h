#pragma once

// The members of VerilatorTraversalDevice<Top, Image>. Included by the .cpp of
// each unit's device only, after its VerilatedTraversalUnit<Top>
// specialization and the Verilated header, followed by
//   template class VerilatorTraversalDevice<Top, Image>;
//
// A specialization VerilatedTraversalUnit<Top> defines (all static, inline)
// only what names the Verilated model's own members:
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

template <class Top, class Image>
TraversalRunStats VerilatorTraversalDevice<Top, Image>::run(const Image& image, std::span<const fx::QRay> rays,
                                                            std::vector<fx::TraversalTrace>& traces,
                                                            const TraversalRunOptions& options) {
  using Unit = VerilatedTraversalUnit<Top>;
  using Desc = typename Unit::Desc;
  const int maxSlots = Unit::kMaxSlots;
  checkTraversalOptions(options, maxSlots, Desc::kNames.unit, Desc::kNames.slotsOption);
  Desc::checkImage(image, rays);

  TraversalRunStats stats;
  const size_t n = rays.size();
  traces.assign(n, fx::TraversalTrace{});
  stats.rays = n;
  if (n == 0) return stats;

  // The records of the two narrow streams, taken straight from their ports.
  constexpr auto kVisitFields = Desc::kVisitFields;
  static_assert(fx::recordBits(kVisitFields) <= 64 && kVisitFields.size() == 2, "a visit is {ray_id, element}");
  constexpr int kVisitRayLsb = trav_detail::fieldLsb(kVisitFields, 0);
  constexpr int kVisitIdLsb = trav_detail::fieldLsb(kVisitFields, 1);
  constexpr int kVisitIdBits = kVisitFields[1].width;
  static_assert(kVisitFields[0].width == 32 && kVisitIdBits <= 32 && kVisitRayLsb + 32 == fx::recordBits(kVisitFields));
  constexpr uint64_t kVisitIdMask = (uint64_t(1) << kVisitIdBits) - 1;
  constexpr size_t kResWords = size_t(fx::wireWords(fx::recordBits(Desc::kResFields)));
  constexpr size_t kTriWords = fx::kIsectTriWords;
  constexpr size_t kNodeWords = size_t(fx::wireWords(fx::kNodeBitsOf<Desc>));
  constexpr size_t kGroupWords = Desc::kGroup * kNodeWords;

  // The image as the ports carry it, packed once: node table (a group is
  // kGroup consecutive elements) and triangles. Nothing is allocated per cycle.
  const auto& nodes = Desc::nodes(image);
  std::vector<uint32_t> nodeWire(nodes.size() * kNodeWords);
  for (size_t i = 0; i < nodes.size(); ++i) {
    fx::packNode<Desc>(nodes[i], std::span<uint32_t>(nodeWire).subspan(kNodeWords * i, kNodeWords));
  }
  std::vector<uint32_t> triWire(image.triangles.size() * kTriWords);
  for (size_t i = 0; i < image.triangles.size(); ++i) {
    fx::packWire(image.triangles[i], std::span<uint32_t>(triWire).subspan(i * kTriWords, kTriWords));
  }

  VerilatedUnit<Top>& unit = *unit_;
  Top& top = unit.top();
  auto [nodeReqValid, nodeReqAddr, nodeReqTag, nodeReqReady, nodeRspValid, nodeRspData, nodeRspTag] =
      Unit::nodePort(top);
  (void)nodeReqReady;  // always ready, set by idleInputs
  static_assert(portWords<std::remove_reference_t<decltype(nodeRspData)>>() == kGroupWords,
                "the node response port does not carry kGroup nodes of the descriptor: rebuild rt_pkg");
  static_assert(portWords<std::remove_reference_t<decltype(top.res_data_o)>>() >= kResWords,
                "res_data_o does not match the unit's result record: rebuild rt_pkg");
  auto configure = [&] {
    top.cfg_slots_i = options.raysInFlight == 0 ? maxSlots : options.raysInFlight;
    trav_detail::configure(top, image);
  };
  unit.reset(trav_detail::idleInputs<Top>);
  configure();
  unit.settle();
  unit.openWave(options.stream.wavePath);

  TraversalStimulus stim(options);
  std::vector<uint8_t> finished(n, 0);
  std::vector<uint32_t> resultElements(n, 0);
  std::array<uint32_t, kResWords> resWire{};
  std::array<fx::u128, fx::valueCount(Desc::kResFields)> res{};
  fx::RayWire rayWire{};
  size_t offered = 0, results = 0;
  bool offering = false, started = false;
  uint64_t firstCycle = 0, lastProgress = unit.cycle();

  auto fail = [](const std::string& what) { throw std::runtime_error("rtl: " + what); };

  try {
    while (results < n || !stim.memoryIdle() || top.visit_valid_o) {
      const uint64_t cycle = unit.cycle();
      // Producer: the next ray, unless idling; an offer holds until taken.
      if (!offering && offered < n && !stim.idle()) {
        fx::QRay wireRay = rays[offered];
        wireRay.id = uint32_t(offered);
        fx::packWire(wireRay, rayWire);
        writePort(top.ray_data_i, rayWire.data(), fx::kIsectRayWords);
        offering = true;
        if (!started) {
          started = true;
          firstCycle = cycle;
        }
      }
      top.ray_valid_i = offering;
      const bool resReady = !stim.stallRes();
      const bool visitReady = !stim.stallVisit();
      top.res_ready_i = resReady;
      top.visit_ready_i = visitReady;

      // Memory responses due in this cycle.
      uint32_t addr = 0, tag = 0;
      nodeRspValid = stim.nodePort.respond(cycle, addr, tag);
      if (nodeRspValid) {
        if (uint64_t(addr) + Desc::kGroup > nodes.size()) {
          fail(fmt::format("{} read at {} outside the {} ({} entries)", Desc::kNames.nodeRead, addr,
                           Desc::kNames.nodeTable, nodes.size()));
        }
        writePort(nodeRspData, &nodeWire[size_t(addr) * kNodeWords], kGroupWords);
        nodeRspTag = tag;
      }
      top.idx_rsp_valid_i = stim.idxPort.respond(cycle, addr, tag);
      if (top.idx_rsp_valid_i) {
        if (addr >= image.indices.size()) {
          fail(fmt::format("index list read at {} outside the image ({} entries)", addr, image.indices.size()));
        }
        top.idx_rsp_data_i = image.indices[addr];
        top.idx_rsp_tag_i = tag;
      }
      top.tri_rsp_valid_i = stim.triPort.respond(cycle, addr, tag);
      if (top.tri_rsp_valid_i) {
        if (addr >= image.triangles.size()) {
          fail(fmt::format("triangle table read at {} outside the image ({} entries)", addr,
                           image.triangles.size()));
        }
        writePort(top.tri_rsp_data_i, &triWire[size_t(addr) * kTriWords], kTriWords);
        top.tri_rsp_tag_i = tag;
      }
      unit.settle();

      // Handshakes of this cycle, read with the inputs settled (perf_isect_fire_o
      // is combinational in tri_rsp_valid_i). The memory ports are always ready.
      const bool rayFire = offering && top.ray_ready_o;
      bool progress = rayFire;
      if (nodeReqValid) {
        stim.nodePort.request(cycle, nodeReqAddr, nodeReqTag);
        ++stats.nodeReads;
      }
      if (top.idx_req_valid_o) {
        stim.idxPort.request(cycle, top.idx_req_addr_o, top.idx_req_tag_o);
        ++stats.indexReads;
      }
      if (top.tri_req_valid_o) {
        stim.triPort.request(cycle, top.tri_req_addr_o, top.tri_req_tag_o);
        ++stats.triangleReads;
      }
      if (top.perf_isect_fire_o) {
        ++stats.isectTests;
        ++stats.isectBusyCycles;
        progress = true;
      }
      if (started && top.perf_step_ready_o) ++stats.stepReadyCycles;
      if (top.visit_valid_o && visitReady) {
        const uint64_t visit = top.visit_data_o;  // {ray_id, element}
        const size_t k = size_t(uint32_t(visit >> kVisitRayLsb));
        if (k >= offered) fail(fmt::format("a visit record for ray {} that was never accepted", k));
        traces[k].visits.push_back(uint32_t((visit >> kVisitIdLsb) & kVisitIdMask));
        ++stats.steps;
        stats.cycles = cycle - firstCycle + 1;
        progress = true;
      }
      if (top.res_valid_o && resReady) {
        readPort(top.res_data_o, resWire.data(), kResWords);
        fx::unpackFields(Desc::kResFields, resWire, res);
        const size_t k = size_t(res[0]);
        if (k >= offered || finished[k]) fail(fmt::format("a result for ray {} that is not in flight", k));
        finished[k] = 1;
        resultElements[k] = fx::takeTraversalResult(res, rays[k].id, traces[k]);
        ++results;
        stats.cycles = cycle - firstCycle + 1;
        progress = true;
      }

      unit.tick();
      if (rayFire) {
        offering = false;
        ++offered;
      }
      if (progress) lastProgress = unit.cycle();
      if (unit.cycle() - lastProgress > kTraversalWatchdogCycles) {
        fail(fmt::format("no progress for {} cycles ({} of {} rays accepted, {} results)", kTraversalWatchdogCycles,
                         offered, n, results));
      }
    }
  } catch (...) {
    unit.closeWave();
    throw;
  }
  trav_detail::idleInputs(top);
  configure();
  unit.settle();
  unit.closeWave();
  for (size_t k = 0; k < n; ++k) {
    if (resultElements[k] != traces[k].visits.size()) {
      fail(fmt::format("ray {} reports {} {} but {} visit records came out", k, resultElements[k],
                       Desc::kNames.elements, traces[k].visits.size()));
    }
  }
  return stats;
}

}  // namespace lancer
