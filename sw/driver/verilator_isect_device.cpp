#include "driver/verilator_isect_device.h"

#include <string>

#include "Vrt_isect.h"
#include "Vrt_quadric.h"
#include "driver/isect_run.h"
#include "driver/verilated_unit.h"

namespace lancer {

VerilatorIsectDevice::VerilatorIsectDevice() : unit_(std::make_unique<VerilatedUnit<Vrt_isect>>("rt_isect")) {
  unit_->reset(isect_detail::idleInputs<Vrt_isect>);
}

VerilatorIsectDevice::~VerilatorIsectDevice() = default;

uint64_t VerilatorIsectDevice::totalCycles() const { return unit_->cycle(); }

StreamStats VerilatorIsectDevice::run(std::span<const IsectRequest> requests,
                                      std::vector<fx::IsectResult>& results,
                                      const StreamOptions& options) {
  return runIsectStream(*unit_, requests, results, options);
}

StreamStats VerilatorIsectDevice::runQuadrics(std::span<const QuadricRequest> requests,
                                              std::vector<fx::IsectResult>& results,
                                              const StreamOptions& options) {
  if (!quadric_) {
    quadric_ = std::make_unique<VerilatedUnit<Vrt_quadric>>("rt_quadric");
    quadric_->reset(isect_detail::idleInputs<Vrt_quadric>);
  }
  return runIsectStream(*quadric_, requests, results, quadricWaves(options));
}

}  // namespace lancer
