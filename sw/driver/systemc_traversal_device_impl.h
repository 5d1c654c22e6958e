#pragma once

// The members of SystemCTraversalDevice<Image, Unit>, for the unit's device
// .cpp (systemc_grid_device.cpp) to instantiate with LANCER_SYSTEMC_TRAVERSAL_UNIT.

#include <array>
#include <mutex>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <systemc>

#include "common/error.h"
#include "common/rt_trav_shell_model.h"
#include "common/rt_trav_top.h"
#include "driver/chip.h"
#include "driver/model_unit.h"
#include "driver/systemc_kernel.h"
#include "driver/systemc_traversal_device.h"
#include "driver/traversal_run.h"
#include "driver/wave_file.h"

namespace lancer {

namespace systemc_kernel {

// A traversal unit's system, built with the others (registerTraversalSystem).
template <class Unit>
sc::rt_trav_top<Unit>*& systemOf() {
  static sc::rt_trav_top<Unit>* system = nullptr;
  return system;
}

template <class Unit>
sc::rt_trav_top<Unit>& traversalSystem() {
  buildSystems();
  sc::use_verilated_context();  // the one context of every Verilated SystemC model
  return *systemOf<Unit>();
}

}  // namespace systemc_kernel

// A traversal unit's cycle model (rt_trav_shell_model's ports: node_*, cfg_i)
// as a clocked top of the run loop (traversal_run.h): the same for every unit.
template <class Model>
concept TraversalCycleModel = requires { typename Model::unit_t; } &&
    std::is_base_of_v<sc::rt_trav_shell_model<typename Model::unit_t, Model::kRegisteredResponses>, Model>;

template <TraversalCycleModel Model>
struct TraversalTop<Model> {
  using Desc = typename Model::unit_t::descriptor;
  static constexpr int kMaxSlots = Model::unit_t::RAYS_IN_FLIGHT;
  static auto nodePort(Model& m) {
    return std::tie(m.node_req_valid_o, m.node_req_addr_o, m.node_req_tag_o, m.node_req_ready_i, m.node_rsp_valid_i,
                    m.node_rsp_data_i, m.node_rsp_tag_i);
  }
  static auto& configPort(Model& m) { return m.cfg_i; }
};

template <class Image, class Unit>
SystemCTraversalDevice<Image, Unit>::~SystemCTraversalDevice() = default;

template <class Image, class Unit>
SystemCTraversalDevice<Image, Unit>::SystemCTraversalDevice(Impl impl) : impl_(impl) {
  if (impl_ == Impl::Rtl && !rtlAvailable()) {
    throw std::runtime_error(
        fmt::format("rtl-systemc is not part of this build (no {})", fx::UnitFor<Image>::kNames.rtlSources));
  }
  if (impl_ == Impl::ModelRtlIsect && !rtlIsectAvailable()) {
    throw std::runtime_error(fmt::format("the {} cycle model with the Verilated rt_isect is not part of this build",
                                         fx::UnitFor<Image>::kNames.module));
  }
}

template <class Image, class Unit>
std::string_view SystemCTraversalDevice<Image, Unit>::name() const {
  switch (impl_) {
    case Impl::Model: return "systemc";
    case Impl::Pins: return "systemc-pins";
    case Impl::Rtl: return "rtl-systemc";
    case Impl::ModelRtlIsect: return "systemc+rtl-isect";
  }
  return "systemc";
}

template <class Image, class Unit>
int SystemCTraversalDevice<Image, Unit>::maxRaysInFlight() const {
  return Unit::RAYS_IN_FLIGHT;
}

template <class Image, class Unit>
bool SystemCTraversalDevice<Image, Unit>::rtlAvailable() {
  return sc::rt_trav_top<Unit>::has_rtl();
}

template <class Image, class Unit>
bool SystemCTraversalDevice<Image, Unit>::rtlIsectAvailable() {
  return sc::rt_trav_top<Unit>::has_rtl_isect();
}

template <class Image, class Unit>
bool SystemCTraversalDevice<Image, Unit>::wavesAvailable() {
  return sc::rt_trav_top<Unit>::has_waves();
}

template <class Image, class Unit>
TraversalRunStats SystemCTraversalDevice<Image, Unit>::run(const Image& image, std::span<const fx::QRay> rays,
                                                           std::vector<fx::TraversalTrace>& traces,
                                                           const TraversalRunOptions& options) {
  using Desc = fx::UnitFor<Image>;
  checkTraversalOptions(options, name(), maxRaysInFlight(), Desc::kNames.unit, Desc::kNames.slotsOption);
  if (impl_ == Impl::ModelRtlIsect) refuseQuadrics(image, name(), Desc::kNames.unit);
  if (impl_ != Impl::Model && options.units > sc::kScChipUnits) {
    throw InputError(fmt::format("--units {}: the SystemC chip of this build has {} units (CMake "
                                 "LANCER_SC_CHIP_UNITS; --model rtl takes up to {})",
                                 options.units, sc::kScChipUnits, kMaxUnits));
  }
  Desc::checkImage(image, rays);
  if (options.treelets && impl_ != Impl::Model) {
    throw InputError(fmt::format("--schedule treelet: the {} model of the {} unit has no ray queues (its SystemC "
                                 "testbench dispatches in order); use --model systemc",
                                 name(), Desc::kNames.unit));
  }
  for (const double p : {options.stream.outputStallProbability, options.stream.inputIdleProbability}) {
    if (!(p >= 0.0 && p < 1.0)) {
      throw InputError(fmt::format("{}: stall and idle probabilities must lie in [0, 1), got {}", name(), p));
    }
  }
  if (impl_ == Impl::Model) {
    using Model = typename Unit::model_t;
    return runTraversalChip(
        models_, [] { return std::make_unique<ModelUnit<Model>>(); }, image, rays, traces, options, trace_);
  }
  const bool wave = impl_ == Impl::Rtl && !options.stream.wavePath.empty();
  if (wave && !wavesAvailable()) {
    throw std::runtime_error("rtl-systemc: this build has no FST tracing (LANCER_SC_RTL_WAVES=OFF)");
  }

  TraversalRunStats stats;
  const size_t n = rays.size();
  traces.assign(n, fx::TraversalTrace{});
  stats.rays = n;
  if (n == 0) return stats;

  sc::rt_trav_job job;
  job.rays.reserve(n);
  job.rayIds.reserve(n);
  std::array<uint32_t, fx::kIsectRayWords> wire{};
  for (size_t k = 0; k < n; ++k) {
    fx::QRay wireRay = rays[k];
    wireRay.id = uint32_t(k);
    fx::packWire(wireRay, wire);
    job.rays.push_back(sc::toPort<sc::ISECT_RAY_W>(wire));
    job.rayIds.push_back(rays[k].id);
  }
  job.slots = uint32_t(options.raysInFlight == 0 ? maxRaysInFlight() : options.raysInFlight);
  job.inputIdleProbability = options.stream.inputIdleProbability;
  job.outputStallProbability = options.stream.outputStallProbability;
  job.seed = options.stream.seed;
  job.traces = &traces;
  job.trace = trace_;

  const sc::rt_trav_impl impl = impl_ == Impl::Rtl ? sc::rt_trav_impl::rtl
                                : impl_ == Impl::ModelRtlIsect ? sc::rt_trav_impl::model_rtl_isect
                                                               : sc::rt_trav_impl::model;
  job.dispatchBatch = options.dispatchBatch;
  const int units = options.units;
  std::unique_ptr<mem::MemorySystem> own;
  mem::MemorySystem& memory = memoryFor<Desc>(options, image, own);

  const std::lock_guard<std::mutex> lock(systemc_kernel::mutex());
  sc::rt_trav_top<Unit>& top = systemc_kernel::traversalSystem<Unit>();
  auto& tb = top.tb(impl);
  if (wave) top.open_wave(nextWaveFile(options.stream.wavePath));
  try {
    tb.start(job, image, memory, units);
    // The units' clocks stop after the run's last cycle, so sc_start() returns
    // by starvation exactly when the run is over.
    sc_core::sc_start();
  } catch (const sc_core::sc_report& report) {
    tb.stop();  // the clocks come to rest at the next sc_start
    if (wave) top.close_wave();
    traces.assign(n, fx::TraversalTrace{});
    throw std::runtime_error(fmt::format("{}: SystemC: {}", name(), report.what()));
  }
  if (wave) top.close_wave();
  if (const std::string error = tb.error(); !error.empty() || !tb.finished()) {
    throw std::runtime_error(fmt::format("{}: run abandoned: {}", name(),
                                         error.empty() ? "the clock stopped early" : error));
  }
  uint64_t first = UINT64_MAX, last = 0;
  std::vector<uint32_t> resultSteps(n, 0);
  for (int u = 0; u < units; ++u) {
    const sc::rt_trav_tally& t = tb.tally(u);
    for (size_t k = 0; k < n; ++k) resultSteps[k] += t.resultSteps[k];
    if (t.started) first = std::min(first, t.firstCycle);
    last = std::max(last, t.lastCycle);
    stats.steps += t.visits;
    stats.stepReadyCycles += t.stepReadyCycles;
    stats.nodeReads += t.nodeReads;
    stats.indexReads += t.indexReads;
    stats.triangleReads += t.triangleReads;
    stats.isectTests += t.isectTests;
    stats.quadricTests += t.quadricTests;
    stats.isectBusyCycles += t.isectTests;  // at most one pair enters a unit per cycle
    stats.unitRays.push_back(t.accepted);
    stats.unitBusyCycles.push_back(t.busyCycles);
  }
  for (size_t k = 0; k < n; ++k) {
    if (resultSteps[k] != traces[k].visits.size()) {
      throw std::runtime_error(fmt::format("{}: ray {} reports {} {} but {} visit records came out", name(), k,
                                           resultSteps[k], Desc::kNames.elements, traces[k].visits.size()));
    }
  }
  stats.cycles = last - first + 1;
  stats.memory = memory.stats();
  stats.cycleAccurate = true;
  return stats;
}

}  // namespace lancer

// A unit's SystemC device, in its systemc_<unit>_device.cpp: the explicit
// instantiation for the descriptor `Descriptor` and the SystemC traits `Traits`
// (systemc/<unit>/rt_<unit>_unit.h), its factories, and its system
// ("lancer_<unit>"), registered with the process's kernel.
#define LANCER_SYSTEMC_TRAVERSAL_UNIT(Descriptor, Traits)                                        \
  namespace lancer {                                                                            \
  namespace {                                                                                   \
  [[maybe_unused]] const bool kSystemRegistered = systemc_kernel::registerTraversalSystem(      \
      int(Descriptor::kKind), [] {                                                              \
        systemc_kernel::systemOf<Traits>() =                                                    \
            new sc::rt_trav_top<Traits>((std::string("lancer_") + Descriptor::kNames.unit).c_str()); \
      });                                                                                       \
  }                                                                                             \
  template class SystemCTraversalDevice<Descriptor::Image, Traits>;                             \
  template <>                                                                                   \
  std::unique_ptr<DeviceOf<Descriptor>> makeSystemCDevice<Descriptor>(SystemCImpl impl) {       \
    return std::make_unique<SystemCTraversalDevice<Descriptor::Image, Traits>>(impl);           \
  }                                                                                             \
  template <>                                                                                   \
  bool systemCRtlAvailable<Descriptor>() {                                                      \
    return SystemCTraversalDevice<Descriptor::Image, Traits>::rtlAvailable();                   \
  }                                                                                             \
  }  // namespace lancer
