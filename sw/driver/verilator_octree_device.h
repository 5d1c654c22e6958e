#pragma once

#include <cstdint>
#include <memory>

#include "driver/traversal_device.h"

class Vrt_octree;

namespace lancer {

template <class Top>
class VerilatedUnit;

// The Verilated RTL of rt_octree (rtl/octree/rt_octree.sv, with its rt_isect)
// behind the OctreeDevice interface, name "rtl". run() resets the model,
// configures the slots to use and the root's record (cfg_root_i =
// image.nodes[0]), offers the rays in order (idling with
// StreamOptions::inputIdleProbability when it has none on offer), deasserts
// res_ready_i and visit_ready_i independently with outputStallProbability,
// and serves the image on the three memory ports (fx::MemoryReadPort each,
// seeds seed*3+1 node, +2 index, +3 triangle; a node request at `first`
// returns the child group first .. first+7). Rays cross the port with ray_id =
// their index in `rays`; the traces get the rays' own ids back. Counts
// TraversalRunStats exactly: cycles from the first ray offered to the last
// result or visit taken, steps = visit records, reads per port from the
// request handshakes, isect tests and busy cycles from perf_isect_fire_o,
// step-ready cycles from perf_step_ready_o. Throws InputError for raysInFlight
// outside 0..maxRaysInFlight(), a memory latency below 1, a ray with a zero
// direction or an image without nodes; runtime_error on a failed assertion,
// an out-of-range address, an inconsistent stream, or 10^6 cycles without
// progress. StreamOptions::wavePath writes an FST waveform.
class VerilatorOctreeDevice final : public OctreeDevice {
 public:
  VerilatorOctreeDevice();
  ~VerilatorOctreeDevice() override;
  VerilatorOctreeDevice(const VerilatorOctreeDevice&) = delete;
  VerilatorOctreeDevice& operator=(const VerilatorOctreeDevice&) = delete;

  std::string_view name() const override { return "rtl"; }
  int maxRaysInFlight() const override;
  TraversalRunStats run(const fx::OctreeImage& image, std::span<const fx::QRay> rays,
                        std::vector<fx::TraversalTrace>& traces, const TraversalRunOptions& options = {}) override;

 private:
  std::unique_ptr<VerilatedUnit<Vrt_octree>> unit_;
};

}  // namespace lancer
