#pragma once

#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "common/rt_trav_cycle.h"
#include "driver/hardware_devices.h"
#include "driver/traversal_device.h"

namespace lancer {

template <class Model>
class ModelUnit;

// A traversal unit's SystemC models (systemc/: the unit's cycle model,
// Unit::model_t, and its RTL Verilated with --sc), behind the unit's
// TraversalDevice interface. Implementations:
//   "systemc"       Impl::Model: the unit's cycle model on value ports (the
//                   fast path: base/rt_value.h), clocked by the run loop
//                   that clocks the Verilated RTL (traversal_run.h over
//                   ModelUnit): no kernel, up to kMaxUnits units;
//   "systemc-pins"  Impl::Pins: the same model bound to sc_in/sc_out
//                   (rt_trav_pin_model) in the SystemC kernel;
//   "rtl-systemc"   Impl::Rtl: the unit's RTL (with its own rt_isect)
//                   Verilated with --sc (Vrt_grid_sc, ...);
//   (unnamed)       Impl::ModelRtlIsect: the pin-level cycle model with the
//                   Verilated rt_isect (Vrt_isect_sc) inside, for mixed runs (rt_grid).
// The kernel's (the last three) are a chip of up to kScChipUnits units on the
// chip's memory system (systemc/common/rt_trav_top.h: rt_trav_tb over
// memory/system.h, one system per process: sw/driver/systemc_kernel.h).
// Every implementation is driven as the C++ Verilated devices drive theirs,
// cycle for cycle, in the same unit order: reset per run, ray
// ids = indices on the port, the same stimulus draws and memory response times
// for the same TraversalRunOptions, and the same TraversalRunStats: cycles
// from the first ray offered to the last result or visit taken, reads per
// region from the request handshakes, tests and busy cycles from
// perf_isect_fire_o, stepReadyCycles from perf_step_ready_o. So "systemc",
// "rtl-systemc" and "rtl" can be compared cycle for cycle.
//
// Throws InputError for raysInFlight outside 0..maxRaysInFlight() (naming both),
// a memory latency < 1 or a negative jitter, stall/idle probabilities outside
// [0, 1), and an image or ray the unit cannot take (its descriptor's checkImage);
// std::runtime_error when a run is abandoned (watchdog: 10^6 cycles without
// progress, inconsistent streams, a model assertion, an address outside the
// image). StreamOptions::wavePath writes an FST for "rtl-systemc" (when built
// with LANCER_SC_RTL_WAVES) and is ignored by the cycle models.
//
// The members are defined in systemc_traversal_device_impl.h and instantiated
// by systemc_<unit>_device.cpp.
template <class Image, class Unit>
class SystemCTraversalDevice final : public TraversalDevice<Image> {
 public:
  using Impl = SystemCImpl;

  explicit SystemCTraversalDevice(Impl impl = Impl::Model);
  ~SystemCTraversalDevice() override;
  SystemCTraversalDevice(const SystemCTraversalDevice&) = delete;
  SystemCTraversalDevice& operator=(const SystemCTraversalDevice&) = delete;

  std::string_view name() const override;
  int maxRaysInFlight() const override;
  TraversalRunStats run(const Image& image, std::span<const fx::QRay> rays, std::vector<fx::TraversalTrace>& traces,
                        const TraversalRunOptions& options = {}) override;

  // Records the port activity of every cycle of the following runs into
  // *trace (appended; nullptr turns it off), from the first ray offered.
  void setCycleTrace(std::vector<sc::TraversalCycle>* trace) { trace_ = trace; }

  // Whether this build has the Verilated unit ("rtl-systemc"), the mixed
  // implementation (Impl::ModelRtlIsect), and FST tracing of the former.
  static bool rtlAvailable();
  static bool rtlIsectAvailable();
  static bool wavesAvailable();

 private:
  TraversalRunStats runKernel(const Image& image, std::span<const fx::QRay> rays,
                              std::vector<fx::TraversalTrace>& traces, const TraversalRunOptions& options);

  Impl impl_;
  std::vector<sc::TraversalCycle>* trace_ = nullptr;
  std::vector<std::unique_ptr<ModelUnit<typename Unit::model_t>>> models_;  // Impl::Model's units, made as runs need them
};

}  // namespace lancer
