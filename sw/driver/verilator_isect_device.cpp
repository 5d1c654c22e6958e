#include "driver/verilator_isect_device.h"

#include <filesystem>
#include <string>

#include "Vrt_isect.h"
#include "Vrt_quadric.h"
#include "driver/isect_run.h"
#include "driver/verilated_unit.h"

namespace lancer {

namespace {

// The quadric pipeline's waveforms sit beside the triangles': x.fst gives
// x.quadric.fst (then x.quadric.1.fst, ...), so that each file holds one module.
StreamOptions quadricWaves(const StreamOptions& options) {
  if (options.wavePath.empty()) return options;
  StreamOptions out = options;
  std::filesystem::path p(options.wavePath);
  const std::string ext = p.extension().string();
  p.replace_extension();
  out.wavePath = p.string() + ".quadric" + ext;
  return out;
}

}  // namespace

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
