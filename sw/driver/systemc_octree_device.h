#pragma once

#include <vector>

#include "common/rt_trav_cycle.h"
#include "driver/traversal_device.h"

namespace lancer {

// The octree unit simulated in SystemC (systemc/octree/), behind the
// OctreeDevice interface: traversal unit -> memory, one system per process
// (rt_octree_top, sw/driver/systemc_kernel.h). Implementations:
//   "systemc"      Impl::Model: rt_octree_model, the hand-written cycle model
//                  (with rt_isect's timing inside);
//   "rtl-systemc"  Impl::Rtl: Vrt_octree_sc, rtl/octree/rt_octree.sv (with its
//                  own rt_isect) Verilated with --sc.
// Each sits on its own testbench and memory model (rt_octree_tb,
// rt_octree_mem), which drive it as the C++ Verilated devices drive theirs:
// reset per run, ray ids = indices on the port, the same stimulus draws and
// memory response times for the same TraversalRunOptions as SystemCGridDevice
// and the C++ Verilated devices, and the same TraversalRunStats: cycles from
// the first ray offered to the last result or visit taken, reads per region
// from the request handshakes, tests and busy cycles from perf_isect_fire_o,
// stepReadyCycles from perf_step_ready_o (some slot in ENTER).
//
// Throws InputError for raysInFlight outside 0..maxRaysInFlight() (naming both),
// a memory latency < 1 or a negative jitter, stall/idle probabilities outside
// [0, 1), an image without a root or deeper than the formats allow;
// std::runtime_error when a run is abandoned (watchdog: 10^6 cycles without
// progress, inconsistent streams, a model assertion, an address outside the
// image). StreamOptions::wavePath writes an FST for "rtl-systemc" (when built
// with LANCER_SC_RTL_WAVES) and is ignored by the cycle model.
class SystemCOctreeDevice final : public OctreeDevice {
 public:
  enum class Impl { Model, Rtl };

  explicit SystemCOctreeDevice(Impl impl = Impl::Model);

  std::string_view name() const override;
  int maxRaysInFlight() const override;
  TraversalRunStats run(const fx::OctreeImage& image, std::span<const fx::QRay> rays,
                        std::vector<fx::TraversalTrace>& traces, const TraversalRunOptions& options = {}) override;

  // Records the port activity of every cycle of the following runs into
  // *trace (appended; nullptr turns it off), from the first ray offered.
  void setCycleTrace(std::vector<sc::TraversalCycle>* trace) { trace_ = trace; }

  // Whether this build has the Verilated rt_octree ("rtl-systemc") and FST tracing of it.
  static bool rtlAvailable();
  static bool wavesAvailable();

 private:
  Impl impl_;
  std::vector<sc::TraversalCycle>* trace_ = nullptr;
};

}  // namespace lancer
