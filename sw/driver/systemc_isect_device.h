#pragma once

#include <vector>

#include "driver/isect_device.h"
#include "isect/rt_isect_cycle.h"

namespace lancer {

// The intersection pipeline's SystemC models (systemc/isect/) behind the
// device interface. Implementations:
//   "systemc"       Impl::Model: rt_isect_model, the hand-written cycle model
//                   on value ports (the fast path: base/rt_value.h), clocked by
//                   the run loop that clocks the Verilated RTL (isect_run.h
//                   over ModelUnit): no kernel;
//   "systemc-pins"  Impl::Pins: the same model bound to sc_in/sc_out
//                   (rt_pipe_pin_model) in the SystemC kernel;
//   "rtl-systemc"   Impl::Rtl: Vrt_isect_sc, rtl/isect/rt_isect.sv Verilated
//                   with --sc.
// Each has the quadric pipeline beside (runQuadrics): rt_quadric_model, in
// the kernel as a pin-level module, and Vrt_quadric_sc.
//
// The kernel's two sit in one SystemC system, each on its own testbench, and
// bind to the same signals. SystemC elaborates once per process and cannot
// instantiate modules after the first sc_start(), so the system is built on
// the first run() in the process and kept (never torn down); every run() of
// any SystemCIsectDevice feeds the chosen bench and calls sc_start() until its
// results are in. Devices can be created, destroyed and mixed freely; kernel
// runs are serialized by a process-wide lock (SystemC has one kernel per
// process). Every implementation resets the unit at the start of every run, so
// a run's results and cycles depend only on its requests and options, and
// draws the stimulus as the C++ Verilated device does (isect_run.h).
//
// Cycles are counted as StreamStats says: from the cycle the first request is
// offered to the cycle the last result is taken, both included. With no
// backpressure that is requests + fx::kIsectLatency, as the golden device reports.
//
// Options: stall/idle probabilities must lie in [0, 1). StreamOptions::wavePath
// writes an FST of the Verilated RTL for "rtl-systemc" (when built with
// LANCER_SC_RTL_WAVES) and is ignored by the cycle model (it has no RTL signals).
class SystemCIsectDevice final : public IsectDevice {
 public:
  enum class Impl { Model, Pins, Rtl };

  explicit SystemCIsectDevice(Impl impl = Impl::Model);

  std::string_view name() const override;
  StreamStats run(std::span<const IsectRequest> requests, std::vector<fx::IsectResult>& results,
                  const StreamOptions& options = {}) override;
  StreamStats runQuadrics(std::span<const QuadricRequest> requests, std::vector<fx::IsectResult>& results,
                          const StreamOptions& options = {}) override;

  // Records the port activity of every cycle of the following runs into
  // *trace (appended; nullptr turns it off). For cycle-for-cycle comparisons.
  void setCycleTrace(std::vector<sc::IsectCycle>* trace) { trace_ = trace; }

  // Whether this build has the Verilated RTL ("rtl-systemc") and its FST tracing.
  static bool rtlAvailable();
  static bool wavesAvailable();

 private:
  template <class Request>
  StreamStats runKernel(std::span<const Request> requests, std::vector<fx::IsectResult>& results,
                        const StreamOptions& options);

  Impl impl_;
  std::vector<sc::IsectCycle>* trace_ = nullptr;
};

}  // namespace lancer
