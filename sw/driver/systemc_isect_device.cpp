#include "driver/systemc_isect_device.h"

#include <array>
#include <mutex>
#include <type_traits>
#include <stdexcept>

#include <fmt/format.h>
#include <systemc>

#include "driver/isect_run.h"
#include "driver/model_unit.h"
#include "driver/systemc_kernel.h"
#include "driver/wave_file.h"
#include "common/error.h"
#include "isect/rt_isect_model.h"
#include "isect/rt_quadric_model.h"
#include "isect/rt_isect_top.h"
#include "isect/rt_isect_types.h"
#include "isect/rt_pipe_kind.h"

namespace lancer {

SystemCIsectDevice::SystemCIsectDevice(Impl impl) : impl_(impl) {
  if (impl_ == Impl::Rtl && !rtlAvailable()) {
    throw std::runtime_error("rtl-systemc is not part of this build (no LANCER_RTL_ISECT_SOURCES)");
  }
}

std::string_view SystemCIsectDevice::name() const {
  switch (impl_) {
    case Impl::Model: return "systemc";
    case Impl::Pins: return "systemc-pins";
    case Impl::Rtl: return "rtl-systemc";
  }
  return "systemc";
}

bool SystemCIsectDevice::rtlAvailable() { return sc::rt_isect_top::has_rtl(); }
bool SystemCIsectDevice::wavesAvailable() { return sc::rt_isect_top::has_waves(); }

namespace {

void checkProbabilities(std::string_view device, const StreamOptions& options) {
  for (const double p : {options.outputStallProbability, options.inputIdleProbability}) {
    if (!(p >= 0.0 && p < 1.0)) {
      throw std::invalid_argument(fmt::format("{}: stall and idle probabilities must lie in [0, 1), got {}",
                                              device, p));
    }
  }
}

// A cycle model of its own per run: reset, and free of other devices' runs
// (no kernel, no lock); on an error the results of the run are taken back.
template <class Model, class Request>
StreamStats runCycleModel(std::span<const Request> requests, std::vector<fx::IsectResult>& results,
                          const StreamOptions& options, std::vector<sc::IsectCycle>* trace) {
  ModelUnit<Model> unit;
  unit.reset(isect_detail::idleInputs<Model>);
  StreamOptions noWave = options;  // the model has no RTL signals; no waveform name is taken
  noWave.wavePath.clear();
  const size_t resultsBefore = results.size();
  try {
    return runIsectStream(unit, requests, results, noWave, trace);
  } catch (...) {
    results.resize(resultsBefore);
    throw;
  }
}

}  // namespace

StreamStats SystemCIsectDevice::run(std::span<const IsectRequest> requests,
                                    std::vector<fx::IsectResult>& results,
                                    const StreamOptions& options) {
  checkProbabilities(name(), options);
  if (impl_ != Impl::Model) return runKernel(requests, results, options);
  return runCycleModel<sc::rt_isect_model>(requests, results, options, trace_);
}

StreamStats SystemCIsectDevice::runQuadrics(std::span<const QuadricRequest> requests,
                                            std::vector<fx::IsectResult>& results,
                                            const StreamOptions& options) {
  checkProbabilities(name(), options);
  if (impl_ != Impl::Model) return runKernel(requests, results, quadricWaves(options));
  return runCycleModel<sc::rt_quadric_model>(requests, results, options, trace_);
}

namespace {

// The pipeline a request enters, and its primitive's port value.
template <class Request>
using KindOf = std::conditional_t<std::is_same_v<Request, IsectRequest>, sc::isect_kind, sc::quadric_kind>;

// A request's primitive as its port's value (its record's wire image).
template <class Kind, class Request>
sc::vl_port_t<Kind::PRIM_W> primitivePort(const Request& r) {
  std::array<uint32_t, size_t(fx::wireWords(Kind::PRIM_W))> wire;  // fixed size: packing allocates nothing
  fx::packWire(isect_detail::primitiveOf(r), wire);
  return sc::toPort<Kind::PRIM_W>(wire);
}

}  // namespace

template <class Request>
StreamStats SystemCIsectDevice::runKernel(std::span<const Request> requests,
                                          std::vector<fx::IsectResult>& results,
                                          const StreamOptions& options) {
  using Kind = KindOf<Request>;
  const bool wave = impl_ == Impl::Rtl && !options.wavePath.empty();
  if (wave && !wavesAvailable()) {
    throw std::runtime_error("rtl-systemc: this build has no FST tracing (LANCER_SC_RTL_WAVES=OFF)");
  }
  StreamStats stats;
  if (requests.empty()) return stats;

  sc::rt_pipe_job<Kind> job;
  job.rays.reserve(requests.size());
  job.prims.reserve(requests.size());
  fx::RayWire rayWire;
  for (const Request& r : requests) {
    fx::packWire(r.ray, rayWire);
    job.rays.push_back(sc::toPort<sc::ISECT_RAY_W>(rayWire));
    job.prims.push_back(primitivePort<Kind>(r));
  }
  job.inputIdleProbability = options.inputIdleProbability;
  job.outputStallProbability = options.outputStallProbability;
  job.seed = options.seed;
  job.results = &results;
  job.trace = trace_;
  const size_t resultsBefore = results.size();
  results.reserve(resultsBefore + requests.size());

  // The process's one SystemC kernel and its systems, shared with the
  // traversal devices (sw/driver/systemc_kernel.h): elaborated together on first use.
  const std::lock_guard<std::mutex> lock(systemc_kernel::mutex());
  sc::rt_isect_top& top = systemc_kernel::isectSystem();
  sc::rt_pipe_tb<Kind>& tb = top.tb<Kind>(impl_ == Impl::Rtl ? sc::rt_isect_impl::rtl : sc::rt_isect_impl::model);
  if (wave) top.open_wave<Kind>(nextWaveFile(options.wavePath));
  try {
    tb.start(job);
    // The bench's clock stops after the last result, so sc_start() returns by
    // starvation exactly when the run is over.
    sc_core::sc_start();
  } catch (const sc_core::sc_report& report) {
    if (wave) top.close_wave();
    results.resize(resultsBefore);
    throw std::runtime_error(fmt::format("{}: SystemC: {}", name(), report.what()));
  }
  if (wave) top.close_wave();
  const sc::rt_pipe_tally& tally = tb.tally();
  if (!tally.error.empty() || tally.busy || tally.taken != requests.size()) {
    results.resize(resultsBefore);
    throw std::runtime_error(fmt::format("{}: run abandoned: {}", name(),
                                         tally.error.empty() ? "the clock stopped early" : tally.error));
  }
  stats.cycles = tally.lastTake - tally.firstOffer + 1;
  stats.requests = tally.accepted;
  stats.results = tally.taken;
  stats.inputStalls = tally.inputStalls;
  stats.cycleAccurate = true;
  return stats;
}

}  // namespace lancer
