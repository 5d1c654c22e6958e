#pragma once

#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "driver/hardware_devices.h"
#include "driver/traversal_device.h"

namespace lancer {

template <class Top>
class VerilatedUnit;
namespace sc {
struct TraversalCycle;
}

// What a Verilated traversal unit (`Top`, e.g. Vrt_grid) brings to the run
// loop: specialized once per unit in its device's .cpp, next to the explicit
// instantiation, so that every member is inlined into the loop.
// traversal_run.h lists the members a specialization defines.
template <class Top>
struct TraversalTop;

// The Verilated RTL of a traversal unit (rt_grid, rt_octree: a traversal with
// its memory ports and its rt_isect) behind TraversalDevice<Image>, name
// "rtl". run() resets the model (VerilatedUnit: its own VerilatedContext,
// selected by every run), configures the slots to use and the unit's own
// configuration (the grid's resolution, the octree's root record), offers the
// rays in order (idling with StreamOptions::inputIdleProbability when it has
// none on offer), deasserts res_ready_i and visit_ready_i independently with
// outputStallProbability, and serves the image on the three memory ports
// (fx::MemoryReadPort each, seeds seed*3+1 node/cell, +2 index, +3 triangle;
// a node request returns the unit's group: one cell, or the child group of
// eight nodes). Rays cross the port with ray_id = their index in `rays`; the
// traces get the rays' own ids back. Counts TraversalRunStats exactly: cycles
// from the first ray offered to the last result or visit taken, steps = visit
// records, reads per port from the request handshakes, isect tests and busy
// cycles from perf_isect_fire_o, step-ready cycles from perf_step_ready_o.
// Throws InputError for raysInFlight outside 0..maxRaysInFlight(), a memory
// latency below 1, a negative jitter, or an image or ray the unit cannot take;
// runtime_error on a failed assertion, an out-of-range address, an
// inconsistent stream, or 10^6 cycles without progress.
// StreamOptions::wavePath writes an FST waveform.
//
// Per cycle the loop does only inlined work on the ports (no virtual call, no
// allocation): the unit's differences are compile-time members of its traits.
template <class Top, class Image>
class VerilatorTraversalDevice final : public TraversalDevice<Image> {
 public:
  VerilatorTraversalDevice();  // builds the model and resets it
  ~VerilatorTraversalDevice() override;
  VerilatorTraversalDevice(const VerilatorTraversalDevice&) = delete;
  VerilatorTraversalDevice& operator=(const VerilatorTraversalDevice&) = delete;

  std::string_view name() const override { return "rtl"; }
  int maxRaysInFlight() const override;  // the unit's compile definition (rtl/CMakeLists.txt)
  TraversalRunStats run(const Image& image, std::span<const fx::QRay> rays, std::vector<fx::TraversalTrace>& traces,
                        const TraversalRunOptions& options = {}) override;

  // Records unit 0's port activity in every cycle of the following runs into
  // *trace (appended; nullptr turns it off), from the first ray offered, as
  // SystemCTraversalDevice::setCycleTrace does.
  void setCycleTrace(std::vector<sc::TraversalCycle>* trace) { portTrace_ = trace; }

 private:
  std::vector<std::unique_ptr<VerilatedUnit<Top>>> units_;  // the chip's units, made as a run needs them
  std::vector<sc::TraversalCycle>* portTrace_ = nullptr;
};

}  // namespace lancer
