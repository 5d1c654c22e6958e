#pragma once

// ModelUnit<Model>: a SystemC cycle model on value ports (a traversal unit's
// Unit::model_t: common/rt_trav_shell_model.h) as a clocked unit of the run
// loop (traversal_run.h), where VerilatedUnit<Top> puts the Verilated RTL:
// the fast path of "systemc". No kernel, no signals, no delta cycles: the
// loop sets the model's input values, settle() evaluates its combinational
// outputs, tick() is the rising edge.

#include <string>
#include <utility>

namespace lancer {

template <class Model>
class ModelUnit {
 public:
  using top_type = Model;
  static constexpr const char* kModel = "systemc";

  template <class... Args>
  explicit ModelUnit(Args&&... args) : model_(std::forward<Args>(args)...) {}

  Model& top() { return model_; }
  void select() {}
  void settle() { model_.settle(); }
  void tick() { model_.clock(); }

  // Reset with every input at the idle values `idle(top)` sets. (The RTL's
  // reset holds rst_ni low for two cycles and runs one idle cycle after: no
  // register changes in either, so the model's reset is one call.)
  template <class Idle>
  void reset(Idle idle) {
    idle(model_);
    model_.reset();
  }

  // A cycle model writes no waveform (the RTL's own: --model rtl, rtl-systemc).
  void openWave(const std::string&) {}
  void closeWave() {}

 private:
  Model model_;
};

}  // namespace lancer
