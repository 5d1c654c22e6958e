#pragma once

// The stage registers of a fixed-latency pipeline with rt_isect's and
// rt_quadric's stage control, for their cycle models: stage s loads when it is
// empty or stage s+1 loads (the last stage: when the consumer is ready), so
// bubbles are squeezed out during output stalls and a full pipeline whose
// result is taken accepts a request in the same cycle. The data registers load
// only with a valid item and are not reset (as the RTL's).

#include <array>
#include <cstddef>

#include "base/rt_value.h"

namespace lancer::sc {

template <int Stages, class Data>
class rt_stall_pipe {
 public:
  static_assert(Stages >= 1);

  // rst_ni low: every stage empty.
  void reset() {
    valid_.fill(false);
    items_ = 0;
  }

  // req_ready_o: stage 0 may load this cycle.
  bool ready(bool resReady) const { return stageReady(resReady)[0]; }

  // The rising edge, the registers read as they were before it: every stage
  // that may load takes its predecessor's item; stage 0 takes a new one,
  // computed by `compute(Data&)`, when `load` (req_valid_i).
  template <class Compute>
  void clock(bool resReady, bool load, Compute&& compute) {
    if (items_ == 0 && !load) return;  // empty and nothing enters: no stage changes
    const std::array<bool, Stages> ready = stageReady(resReady);
    items_ -= int(valid_[Stages - 1] && ready[Stages - 1]);
    items_ += int(load && ready[0]);
    // From the output back to the entry: stage s-1 is read before it is written.
    for (size_t s = Stages - 1; s > 0; --s) {
      if (!ready[s]) continue;  // stalled: holds its item
      if (valid_[s - 1]) data_[s] = data_[s - 1];
      valid_[s] = valid_[s - 1];
    }
    if (ready[0]) {
      if (load) compute(data_[0]);
      valid_[0] = load;
    }
  }

  bool outValid() const { return valid_[Stages - 1]; }
  const Data& out() const { return data_[Stages - 1]; }

 private:
  // stage_ready[s] of the RTL.
  std::array<bool, Stages> stageReady(bool resReady) const {
    std::array<bool, Stages> ready{};
    ready[Stages - 1] = !valid_[Stages - 1] || resReady;
    for (int s = Stages - 2; s >= 0; --s) ready[size_t(s)] = !valid_[size_t(s)] || ready[size_t(s) + 1];
    return ready;
  }

  std::array<bool, Stages> valid_{};
  std::array<Data, Stages> data_{};
  int items_ = 0;  // valid stages
};

// The cycle model of such a pipeline on value ports (`Ports`: its port list
// over rt_value, e.g. rt_isect_ports<rt_value, rt_value, value_t>), under the
// RTL's names: the entry stage computes the whole result with
// Derived::compute(res_t&) (from the golden model), the other stages only carry
// it. The caller orders evaluation: set the inputs, settle() for req_ready_o,
// clock() at the rising edge.
template <class Derived, class Ports, int Stages, int ResW>
struct rt_pipe_model : Ports {
  static constexpr int NUM_STAGES = Stages;
  using res_t = value_t<ResW>;

  // rst_ni low: every stage empty; the outputs settled.
  void reset() {
    pipe_.reset();
    writeOutputs();
    settle();
  }
  // req_ready_o from res_ready_i and the registers.
  void settle() { this->req_ready_o = pipe_.ready(this->res_ready_i.value); }
  // The rising edge: the stages load from the inputs and the registers as they
  // were before it; the registered outputs, then settle().
  void clock() {
    pipe_.clock(this->res_ready_i.value, this->req_valid_i.value,
                [this](res_t& out) { static_cast<Derived*>(this)->compute(out); });
    writeOutputs();
    settle();
  }

 private:
  void writeOutputs() {
    this->res_valid_o = pipe_.outValid();
    this->res_data_o = pipe_.out();
  }

  rt_stall_pipe<Stages, res_t> pipe_;
};

}  // namespace lancer::sc
