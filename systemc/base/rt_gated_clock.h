#pragma once

#include <systemc>

namespace lancer::sc {

// rt_gated_clock: the 10 ns clock of a testbench, driven on its own output
// port and running only between start() and stop() (after stop() it finishes
// its period and rests low), so that sc_start() returns by starvation when a
// run is over. An SC_METHOD with next_trigger, as the accellera examples' clocks.
class rt_gated_clock : public sc_core::sc_module {
 public:
  static constexpr double CLOCK_PERIOD_NS = 10.0;

  sc_core::sc_out<bool> clk_o{"clk_o"};

  SC_HAS_PROCESS(rt_gated_clock);
  explicit rt_gated_clock(sc_core::sc_module_name name) : sc_core::sc_module(name) {
    SC_METHOD(toggle);
    sensitive << start_;
    dont_initialize();
  }

  void start() {
    running_ = true;
    start_.notify(sc_core::SC_ZERO_TIME);
  }
  // The current rising edge is the run's last.
  void stop() { running_ = false; }

 private:
  void toggle() {
    const bool level = clk_o.read();
    if (!level && !running_) return;  // at rest, low, until the next start()
    clk_o.write(!level);
    next_trigger(halfPeriod_);
  }

  bool running_ = false;
  sc_core::sc_event start_;
  const sc_core::sc_time halfPeriod_{CLOCK_PERIOD_NS / 2, sc_core::SC_NS};
};

}  // namespace lancer::sc
