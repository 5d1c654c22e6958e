#pragma once

#include <cstdint>
#include <memory>

#include "driver/traversal_device.h"

class Vrt_grid;
class VerilatedContext;
class VerilatedFstC;

namespace lancer {

// The Verilated RTL of rt_grid (rtl/grid/rt_grid.sv, with its rt_isect) behind
// the GridDevice interface, name "rtl". run() resets the model, configures the
// resolution and the slots to use, offers the rays in order (idling with
// StreamOptions::inputIdleProbability when it has none on offer), deasserts
// res_ready_i and visit_ready_i independently with outputStallProbability,
// and serves the image on the three memory ports (fx::MemoryReadPort each). Rays
// cross the port with ray_id = their index in `rays`; the traces get the rays'
// own ids back. Counts TraversalRunStats exactly: cycles from the first ray offered
// to the last result or visit taken, reads per port from the request
// handshakes, isect tests and busy cycles from perf_isect_fire_o, cycles with
// a step ready (stepReadyCycles) from perf_step_ready_o. Throws
// InputError for raysInFlight outside 0..maxRaysInFlight(), runtime_error on a
// failed assertion, an out-of-range address, an inconsistent stream, or 10^6
// cycles without progress. StreamOptions::wavePath writes an FST waveform.
class VerilatorGridDevice final : public GridDevice {
 public:
  VerilatorGridDevice();
  ~VerilatorGridDevice() override;
  VerilatorGridDevice(const VerilatorGridDevice&) = delete;
  VerilatorGridDevice& operator=(const VerilatorGridDevice&) = delete;

  std::string_view name() const override { return "rtl"; }
  int maxRaysInFlight() const override;
  TraversalRunStats run(const fx::GridImage& image, std::span<const fx::QRay> rays, std::vector<fx::GridTrace>& traces,
                   const TraversalRunOptions& options = {}) override;

 private:
  void reset();
  void tick();
  void checkAssertions() const;

  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Vrt_grid> top_;
  std::unique_ptr<VerilatedFstC> wave_;
  uint64_t cycle_ = 0;
};

}  // namespace lancer
