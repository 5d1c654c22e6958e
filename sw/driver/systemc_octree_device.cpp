#include "driver/systemc_octree_device.h"

#include <mutex>
#include <stdexcept>

#include <fmt/format.h>
#include <systemc>

#include "common/error.h"
#include "driver/systemc_kernel.h"
#include "octree/rt_octree_top.h"
#include "octree/rt_octree_types.h"

namespace lancer {

SystemCOctreeDevice::SystemCOctreeDevice(Impl impl) : impl_(impl) {
  if (impl_ == Impl::Rtl && !rtlAvailable()) {
    throw std::runtime_error("rtl-systemc is not part of this build (no Verilated rtl/octree/rt_octree.sv)");
  }
}

std::string_view SystemCOctreeDevice::name() const { return impl_ == Impl::Rtl ? "rtl-systemc" : "systemc"; }
int SystemCOctreeDevice::maxRaysInFlight() const { return sc::octree::RAYS_IN_FLIGHT; }
bool SystemCOctreeDevice::rtlAvailable() { return sc::rt_octree_top::has_rtl(); }
bool SystemCOctreeDevice::wavesAvailable() { return sc::rt_octree_top::has_waves(); }

TraversalRunStats SystemCOctreeDevice::run(const fx::OctreeImage& image, std::span<const fx::QRay> rays,
                                           std::vector<fx::TraversalTrace>& traces,
                                           const TraversalRunOptions& options) {
  const int maxSlots = maxRaysInFlight();
  if (options.raysInFlight < 0 || options.raysInFlight > maxSlots) {
    throw InputError(fmt::format("rays in flight {} is out of range: the SystemC octree unit ({}) has {} ray slots "
                                 "(use 1..{}, or 0 for all; rebuild with -DLANCER_OCTREE_RAYS_IN_FLIGHT for more)",
                                 options.raysInFlight, name(), maxSlots, maxSlots));
  }
  if (options.memLatency < 1 || options.memLatencyJitter < 0) {
    throw InputError(fmt::format("memory latency {} (jitter {}) is out of range: latency >= 1, jitter >= 0",
                                 options.memLatency, options.memLatencyJitter));
  }
  for (const double p : {options.stream.outputStallProbability, options.stream.inputIdleProbability}) {
    if (!(p >= 0.0 && p < 1.0)) {
      throw InputError(fmt::format("{}: stall and idle probabilities must lie in [0, 1), got {}", name(), p));
    }
  }
  if (image.nodes.empty()) throw InputError("the octree image has no root node");
  if (image.depth > fx::kOctreeMaxDepth) {
    throw InputError(fmt::format("octree depth {} exceeds the unit's stack ({} levels)", image.depth,
                                 fx::kOctreeMaxDepth));
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

  sc::rt_octree_job job;
  job.image = &image;
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
  job.slots = uint32_t(options.raysInFlight == 0 ? maxSlots : options.raysInFlight);
  job.inputIdleProbability = options.stream.inputIdleProbability;
  job.outputStallProbability = options.stream.outputStallProbability;
  job.seed = options.stream.seed;
  job.traces = &traces;
  job.trace = trace_;

  const sc::rt_octree_impl impl = impl_ == Impl::Rtl ? sc::rt_octree_impl::rtl : sc::rt_octree_impl::model;
  const std::lock_guard<std::mutex> lock(systemc_kernel::mutex());
  sc::rt_octree_top& top = systemc_kernel::octreeSystem();
  sc::rt_octree_tb& tb = top.tb(impl);
  sc::rt_octree_mem& mem = top.mem(impl);
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
    traces.assign(n, fx::TraversalTrace{});
    throw std::runtime_error(fmt::format("{}: SystemC: {}", name(), report.what()));
  }
  mem.stop();
  if (wave) top.close_wave();
  const sc::rt_trav_tally& tally = tb.tally();
  if (!tally.error.empty() || tally.busy || tally.results != n) {
    throw std::runtime_error(fmt::format("{}: run abandoned: {}", name(),
                                         tally.error.empty() ? "the clock stopped early" : tally.error));
  }
  for (size_t k = 0; k < n; ++k) {
    if (tally.resultSteps[k] != traces[k].visits.size()) {
      throw std::runtime_error(fmt::format("{}: ray {} reports {} nodes but {} visit records came out", name(), k,
                                           tally.resultSteps[k], traces[k].visits.size()));
    }
  }
  stats.cycles = tally.cycles;
  stats.steps = tally.visits;
  stats.stepReadyCycles = tally.stepReadyCycles;
  stats.nodeReads = tally.nodeReads;
  stats.indexReads = tally.indexReads;
  stats.triangleReads = tally.triangleReads;
  stats.isectTests = tally.isectTests;
  stats.isectBusyCycles = tally.isectTests;  // at most one pair enters per cycle
  stats.cycleAccurate = true;
  return stats;
}

}  // namespace lancer
