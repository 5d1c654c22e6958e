#pragma once

#include <cstdint>
#include <memory>

#include "driver/isect_device.h"

class Vrt_isect;
class Vrt_quadric;

namespace lancer {

template <class Top>
class VerilatedUnit;

// The Verilated RTL of rt_isect (rtl/isect/rt_isect.sv) and of rt_quadric
// (rtl/isect/rt_quadric.sv, runQuadrics) behind the device interface. run() drives the model one clock at a time through its valid/ready
// ports (isect_run.h, the loop that clocks the SystemC cycle model too):
// requests are offered in order (the producer idles with
// StreamOptions::inputIdleProbability when it has nothing on offer, and holds
// an offered request until it is taken), the consumer deasserts res_ready_i
// with StreamOptions::outputStallProbability, both from StreamOptions::seed.
// Records cross the ports as whole words (fx::packWire / fx::unpackResult; the
// wire images have Verilator's word order). Cycles are counted exactly, from
// the first cycle a request is offered to the cycle the last result is taken.
// An FST waveform is written when StreamOptions::wavePath is set (off by
// default). A failed SVA assertion in the RTL makes run() throw, and so does a
// stream without a transfer for 10^6 cycles (a lost item, or a probability of 1).
// The model runs in a VerilatedContext of its own (VerilatedUnit), which run()
// makes the thread's current one, so that its assertion failures are reported
// here even when other Verilated models were made after it.
class VerilatorIsectDevice final : public IsectDevice {
 public:
  VerilatorIsectDevice();  // builds the model and resets it
  ~VerilatorIsectDevice() override;
  VerilatorIsectDevice(const VerilatorIsectDevice&) = delete;
  VerilatorIsectDevice& operator=(const VerilatorIsectDevice&) = delete;

  std::string_view name() const override { return "rtl"; }
  StreamStats run(std::span<const IsectRequest> requests, std::vector<fx::IsectResult>& results,
                  const StreamOptions& options = {}) override;
  // rt_quadric, Verilated, in a context of its own, built on the first call;
  // its waveform (StreamOptions::wavePath x.fst) goes to x.quadric.fst.
  StreamStats runQuadrics(std::span<const QuadricRequest> requests, std::vector<fx::IsectResult>& results,
                          const StreamOptions& options = {}) override;

  // Clock edges since construction (reset included); the waveform's time base.
  uint64_t totalCycles() const;

 private:
  std::unique_ptr<VerilatedUnit<Vrt_isect>> unit_;
  std::unique_ptr<VerilatedUnit<Vrt_quadric>> quadric_;
};

}  // namespace lancer
