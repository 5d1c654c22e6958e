#pragma once

#include "driver/isect_device.h"

namespace lancer {

// The golden model behind the device interface: bit-accurate results, and the
// ideal timing of a pipeline with initiation interval 1 (one request per cycle
// when the producer offers one and the consumer is ready, results after
// kIsectLatency cycles; kQuadricLatency for the quadric pipeline). It honours the stall options so its ideal cycle count
// stays comparable with the cycle-accurate models.
class GoldenIsectDevice final : public IsectDevice {
 public:
  std::string_view name() const override { return "golden"; }
  StreamStats run(std::span<const IsectRequest> requests, std::vector<fx::IsectResult>& results,
                  const StreamOptions& options = {}) override;
  StreamStats runQuadrics(std::span<const QuadricRequest> requests, std::vector<fx::IsectResult>& results,
                          const StreamOptions& options = {}) override;
};

}  // namespace lancer
