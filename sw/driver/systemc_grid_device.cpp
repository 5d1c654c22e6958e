#include "driver/systemc_grid_device.h"

#include <mutex>
#include <stdexcept>

#include <fmt/format.h>
#include <systemc>

#include "common/error.h"
#include "driver/systemc_kernel.h"
#include "grid/rt_grid_top.h"
#include "grid/rt_grid_types.h"

namespace lancer {

namespace {

sc::rt_grid_impl toImpl(SystemCGridDevice::Impl impl) {
  switch (impl) {
    case SystemCGridDevice::Impl::Model: return sc::rt_grid_impl::model;
    case SystemCGridDevice::Impl::Rtl: return sc::rt_grid_impl::rtl;
    case SystemCGridDevice::Impl::ModelRtlIsect: return sc::rt_grid_impl::model_rtl_isect;
  }
  return sc::rt_grid_impl::model;
}

}  // namespace

SystemCGridDevice::SystemCGridDevice(Impl impl) : impl_(impl) {
  if (impl_ == Impl::Rtl && !rtlAvailable()) {
    throw std::runtime_error("rtl-systemc is not part of this build (no LANCER_RTL_GRID_SOURCES)");
  }
  if (impl_ == Impl::ModelRtlIsect && !rtlIsectAvailable()) {
    throw std::runtime_error("the Verilated rt_isect is not part of this build (no LANCER_RTL_ISECT_SOURCES)");
  }
}

std::string_view SystemCGridDevice::name() const {
  switch (impl_) {
    case Impl::Model: return "systemc";
    case Impl::Rtl: return "rtl-systemc";
    case Impl::ModelRtlIsect: return "systemc+rtl-isect";
  }
  return "systemc";
}

int SystemCGridDevice::maxRaysInFlight() const { return sc::RAYS_IN_FLIGHT; }
bool SystemCGridDevice::rtlAvailable() { return sc::rt_grid_top::has_rtl(); }
bool SystemCGridDevice::rtlIsectAvailable() { return sc::rt_grid_top::has_rtl_isect(); }
bool SystemCGridDevice::wavesAvailable() { return sc::rt_grid_top::has_waves(); }

TraversalRunStats SystemCGridDevice::run(const fx::GridImage& image, std::span<const fx::QRay> rays,
                                    std::vector<fx::GridTrace>& traces, const TraversalRunOptions& options) {
  const int maxSlots = maxRaysInFlight();
  if (options.raysInFlight < 0 || options.raysInFlight > maxSlots) {
    throw InputError(fmt::format("rays in flight {} is out of range: the SystemC grid unit ({}) has {} ray slots "
                                 "(use 1..{}, or 0 for all; rebuild with -DLANCER_GRID_RAYS_IN_FLIGHT for more)",
                                 options.raysInFlight, name(), maxSlots, maxSlots));
  }
  if (options.memLatency < 1 || options.memLatencyJitter < 0) {
    throw InputError(fmt::format("memory latency {} (jitter {}) is out of range: latency >= 1, jitter >= 0",
                                 options.memLatency, options.memLatencyJitter));
  }
  for (int a = 0; a < 3; ++a) {
    if (image.res[a] < 1 || image.res[a] > fx::kGridResMax) {
      throw InputError(fmt::format("grid resolution {} on axis {} is out of range 1..{}", image.res[a], a,
                                   fx::kGridResMax));
    }
  }
  for (const double p : {options.stream.outputStallProbability, options.stream.inputIdleProbability}) {
    if (!(p >= 0.0 && p < 1.0)) {
      throw InputError(fmt::format("{}: stall and idle probabilities must lie in [0, 1), got {}", name(), p));
    }
  }
  const bool wave = impl_ == Impl::Rtl && !options.stream.wavePath.empty();
  if (wave && !wavesAvailable()) {
    throw std::runtime_error("rtl-systemc: this build has no FST tracing (LANCER_SC_RTL_WAVES=OFF)");
  }

  TraversalRunStats stats;
  const size_t n = rays.size();
  traces.assign(n, fx::GridTrace{});
  stats.rays = n;
  if (n == 0) return stats;

  sc::rt_grid_job job;
  job.image = &image;
  job.rays.reserve(n);
  job.rayIds.reserve(n);
  for (size_t k = 0; k < n; ++k) {
    fx::QRay wireRay = rays[k];
    wireRay.id = uint32_t(k);
    job.rays.push_back(sc::toPort<sc::ISECT_RAY_W>(fx::packWire(wireRay)));
    job.rayIds.push_back(rays[k].id);
  }
  job.slots = uint32_t(options.raysInFlight == 0 ? maxSlots : options.raysInFlight);
  job.inputIdleProbability = options.stream.inputIdleProbability;
  job.outputStallProbability = options.stream.outputStallProbability;
  job.seed = options.stream.seed;
  job.traces = &traces;
  job.trace = trace_;

  const std::lock_guard<std::mutex> lock(systemc_kernel::mutex());
  sc::rt_grid_top& top = systemc_kernel::gridSystem();
  sc::rt_grid_tb& tb = top.tb(toImpl(impl_));
  sc::rt_grid_mem& mem = top.mem(toImpl(impl_));
  if (wave) top.open_wave(options.stream.wavePath);
  try {
    mem.start(image, options.memLatency, options.memLatencyJitter, options.stream.seed);
    tb.start(job);
    // The bench's clock stops after the run's last cycle, so sc_start() returns
    // by starvation exactly when the run is over.
    sc_core::sc_start();
  } catch (const sc_core::sc_report& report) {
    mem.stop();
    if (wave) top.close_wave();
    traces.assign(n, fx::GridTrace{});
    throw std::runtime_error(fmt::format("{}: SystemC: {}", name(), report.what()));
  }
  mem.stop();
  if (wave) top.close_wave();
  const sc::rt_grid_tally& tally = tb.tally();
  if (!tally.error.empty() || tally.busy || tally.results != n) {
    throw std::runtime_error(fmt::format("{}: run abandoned: {}", name(),
                                         tally.error.empty() ? "the clock stopped early" : tally.error));
  }
  for (size_t k = 0; k < n; ++k) {
    if (tally.resultCells[k] != traces[k].visits.size()) {
      throw std::runtime_error(fmt::format("{}: ray {} reports {} cells but {} visit records came out", name(), k,
                                           tally.resultCells[k], traces[k].visits.size()));
    }
  }
  stats.cycles = tally.cycles;
  stats.steps = tally.visits;
  stats.nodeReads = tally.nodeReads;
  stats.indexReads = tally.indexReads;
  stats.triangleReads = tally.triangleReads;
  stats.isectTests = tally.isectTests;
  stats.stepReadyCycles = tally.stepReadyCycles;
  stats.isectBusyCycles = tally.isectTests;  // at most one pair enters per cycle
  stats.cycleAccurate = true;
  return stats;
}

}  // namespace lancer
