#pragma once

#include <vector>

#include "driver/traversal_device.h"
#include "grid/rt_grid_cycle.h"

namespace lancer {

// The grid unit simulated in SystemC (systemc/grid/), behind the GridDevice
// interface: traversal unit -> intersection pipeline -> memory, one system per
// process (rt_grid_top, sw/driver/systemc_kernel.h). Implementations:
//   "systemc"      Impl::Model: rt_grid_model with rt_isect_model inside, the
//                  hand-written cycle models;
//   "rtl-systemc"  Impl::Rtl: Vrt_grid_sc, rtl/grid/rt_grid.sv (with its own
//                  rt_isect) Verilated with --sc;
//   (unnamed)      Impl::ModelRtlIsect: rt_grid_model with the Verilated
//                  rt_isect (Vrt_isect_sc) inside, for mixed runs.
// Each sits on its own testbench and memory model (rt_grid_tb, rt_grid_mem),
// which drive it exactly as VerilatorGridDevice ("rtl") drives the C++
// Verilated model: the same reset-per-run, ray ids = indices, stimulus draws
// and memory response times for the same TraversalRunOptions, and the same
// TraversalRunStats: cycles from the first ray offered to the last result or visit
// taken, reads per region from the request handshakes, tests and busy cycles
// from perf_isect_fire_o, cycles with a step ready from perf_step_ready_o. So
// "systemc", "rtl-systemc" and "rtl" can be compared cycle for cycle.
//
// Throws InputError for raysInFlight outside 0..maxRaysInFlight() (naming both),
// a memory latency < 1 or a negative jitter, a resolution outside 1..256, and
// stall/idle probabilities outside [0, 1); std::runtime_error when a run is
// abandoned (watchdog: 10^6 cycles without progress, inconsistent streams, a
// model assertion, an address outside the image). StreamOptions::wavePath
// writes an FST for "rtl-systemc" (when built with LANCER_SC_RTL_WAVES) and is
// ignored by the cycle model.
class SystemCGridDevice final : public GridDevice {
 public:
  enum class Impl { Model, Rtl, ModelRtlIsect };

  explicit SystemCGridDevice(Impl impl = Impl::Model);

  std::string_view name() const override;
  int maxRaysInFlight() const override;
  TraversalRunStats run(const fx::GridImage& image, std::span<const fx::QRay> rays, std::vector<fx::GridTrace>& traces,
                   const TraversalRunOptions& options = {}) override;

  // Records the port activity of every cycle of the following runs into
  // *trace (appended; nullptr turns it off), from the first ray offered.
  void setCycleTrace(std::vector<sc::GridCycle>* trace) { trace_ = trace; }

  // Whether this build has the Verilated rt_grid ("rtl-systemc"), the
  // Verilated rt_isect (Impl::ModelRtlIsect), and FST tracing of the former.
  static bool rtlAvailable();
  static bool rtlIsectAvailable();
  static bool wavesAvailable();

 private:
  Impl impl_;
  std::vector<sc::GridCycle>* trace_ = nullptr;
};

}  // namespace lancer
