#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <random>

#include "driver/traversal_device.h"

class Vrt_grid;
class VerilatedContext;
class VerilatedFstC;

namespace lancer {

// One read port of the grid unit's memory (cell table, index list or triangle
// table): accepts one request per cycle (req_ready is always 1) and answers it
// memLatency + U(0..memLatencyJitter) cycles later (seeded), never before the
// previous response of the same port, at most one response per cycle: responses
// stay in request order. A request accepted in cycle c with delay L is answered
// (rsp_valid high) in cycle c + L at the earliest.
class GridMemoryPort {
 public:
  GridMemoryPort(int latency, int jitter, uint64_t seed) : latency_(latency), jitter_(jitter), rng_(seed) {}
  void request(uint64_t cycle, uint32_t addr, uint32_t tag);
  // The request answered in `cycle`, if any (removed from the port).
  bool respond(uint64_t cycle, uint32_t& addr, uint32_t& tag);
  bool idle() const { return pending_.empty(); }

 private:
  struct Pending {
    uint64_t due;
    uint32_t addr, tag;
  };
  int latency_, jitter_;
  std::mt19937_64 rng_;
  std::deque<Pending> pending_;
  uint64_t lastDue_ = 0;
};

// The Verilated RTL of rt_grid (rtl/grid/rt_grid.sv, with its rt_isect) behind
// the GridDevice interface, name "rtl". run() resets the model, configures the
// resolution and the slots to use, offers the rays in order (idling with
// StreamOptions::inputIdleProbability when it has none on offer), deasserts
// res_ready_i and visit_ready_i independently with outputStallProbability,
// and serves the image on the three memory ports (GridMemoryPort each). Rays
// cross the port with ray_id = their index in `rays`; the traces get the rays'
// own ids back. Counts TraversalRunStats exactly: cycles from the first ray offered
// to the last result or visit taken, reads per port from the request
// handshakes, isect tests and busy cycles from perf_isect_fire_o. Throws
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
