#pragma once

// What every Verilated device (VerilatorIsectDevice, and the traversal
// devices of verilator_traversal_device.h) does the same way around its own
// ports: owning the Verilated model in a VerilatedContext of its own,
// clocking it one cycle at a time with two evaluations per cycle, the FST
// waveform, turning a failed SVA assertion into an exception. (The traversal
// units' run loop, options and stimulus: traversal_run.h.)

#include <cstdint>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/rtl_coverage.h"
#include "driver/traversal_device.h"
#include "golden/stimulus.h"
#include "verilated.h"
#include "verilated_fst_c.h"

namespace lancer {

// A Verilated model (`Top`, with ports clk_i and rst_ni) and its clock.
//
// Cycle discipline (two evaluations per cycle): at the start of a cycle the
// outputs that depend on registers only are valid (the previous edge's
// evaluation computed them); the caller reads them, sets the inputs of the
// cycle and calls settle(), which evaluates the combinational logic with clk_i
// low (outputs combinational in an input are then valid too), then tick(),
// the rising edge that samples those inputs. The SVA checks sample their
// signals at the edge, so the inputs must be settled before it.
template <class Top>
class VerilatedUnit {
 public:
  using top_type = Top;
  static constexpr const char* kModel = "rtl";

  explicit VerilatedUnit(std::string name) : name_(std::move(name)), context_(std::make_unique<VerilatedContext>()) {
    context_->traceEverOn(true);
    context_->fatalOnError(false);  // a failed assertion becomes an exception (checkAssertions)
    top_ = std::make_unique<Top>(context_.get(), name_.c_str());
    rtl_coverage::attach(*context_);  // no-op unless LANCER_RTL_COVERAGE
  }
  // Verilator reports errors (a failed assertion's $stop) to, and destroys
  // scopes through, the calling thread's current context: the last one
  // created or selected, whichever model it belongs to. So the unit selects
  // its own context before it runs the model (reset; a device that runs
  // without a reset calls select()) and before destroying it, then hands the
  // thread back to the context that was current.
  ~VerilatedUnit() {
    VerilatedContext* const previous = Verilated::threadContextp();
    VerilatedContext* const mine = context_.get();
    select();
    closeWave();
    rtl_coverage::detach(*context_);
    if (top_) top_->final();
    top_.reset();
    context_.reset();
    Verilated::threadContextp(previous != mine ? previous : Verilated::defaultContextp());
  }
  VerilatedUnit(const VerilatedUnit&) = delete;
  VerilatedUnit& operator=(const VerilatedUnit&) = delete;

  Top& top() { return *top_; }
  uint64_t cycle() const { return cycle_; }

  // rst_ni low for two cycles, then high for one, with every input at the
  // idle values `idle(top)` sets; clears the error of an earlier run.
  template <class Idle>
  void reset(Idle idle) {
    select();
    context_->gotError(false);  // a failed assertion of an earlier run is reported already
    context_->gotFinish(false);
    top_->rst_ni = 0;
    idle(*top_);
    step(2);
    top_->rst_ni = 1;
    step();
  }

  // The inputs set for this cycle through the combinational logic (clk_i low).
  void settle() {
    top_->clk_i = 0;
    top_->eval();
  }

  // The rising edge that ends the current cycle (after settle()).
  void tick() {
    if (wave_) wave_->dump(2 * cycle_);
    context_->time(2 * cycle_ + 1);
    top_->clk_i = 1;
    top_->eval();
    if (wave_) wave_->dump(2 * cycle_ + 1);
    ++cycle_;
    context_->time(2 * cycle_);
    checkAssertions();
  }

  // `cycles` whole cycles with the inputs as they stand: settle(), then tick(), each.
  void step(int cycles = 1) {
    for (int i = 0; i < cycles; ++i) {
      settle();
      tick();
    }
  }

  // Makes this unit's context the calling thread's (see the destructor).
  void select() { Verilated::threadContextp(context_.get()); }

  void checkAssertions() const {
    if (context_->gotError()) {
      throw std::runtime_error(
          fmt::format("rtl: an assertion of {} failed near cycle {} (see the %Error line above)", name_, cycle_));
    }
  }

  void openWave(const std::string& path) {
    closeWave();
    if (path.empty()) return;
    wave_ = std::make_unique<VerilatedFstC>();
    top_->trace(wave_.get(), 99);
    wave_->open(path.c_str());
    if (!wave_->isOpen()) {
      wave_.reset();
      throw std::runtime_error("rtl: cannot write waveform " + path);
    }
  }
  void closeWave() {
    if (!wave_) return;
    wave_->dump(2 * cycle_);
    wave_->close();
    wave_.reset();
  }

 private:
  std::string name_;
  std::unique_ptr<VerilatedContext> context_;
  std::unique_ptr<Top> top_;
  std::unique_ptr<VerilatedFstC> wave_;
  uint64_t cycle_ = 0;
};

}  // namespace lancer
