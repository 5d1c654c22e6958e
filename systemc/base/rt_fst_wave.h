#pragma once

#include <functional>
#include <memory>
#include <string>

class VerilatedFstSc;

namespace lancer::sc {

// rt_fst_wave: the FST waveform of one Verilated SystemC model (a top's RTL
// bench), opened and dropped again per run (rt_isect_top, rt_trav_top).
// VerilatedFstSc registers itself with the kernel in its constructor but never
// unregisters (it expects to live until exit); close() takes it off the
// kernel's list, so that one FST per run can be opened and dropped. Without
// FST tracing in the build (LANCER_SC_RTL_WAVES=OFF) open() throws.
class rt_fst_wave {
 public:
  rt_fst_wave();
  ~rt_fst_wave();

  static bool available();  // the Verilated models were built with FST tracing

  // Creates the FST, lets `attach` trace the model into it (model.trace(fst, levels)),
  // opens `path`; throws std::runtime_error when it cannot. Closes a previous one first.
  void open(const std::string& path, const std::function<void(VerilatedFstSc*)>& attach);
  void close();

 private:
  struct state;  // the open FST, when the build has FST tracing
  std::unique_ptr<state> state_;
};

}  // namespace lancer::sc
