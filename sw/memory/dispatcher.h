#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace lancer {

// The dispatcher: every unit holds a batch of consecutive rays (ids) to
// offer, one at a time; at the end of each cycle, in unit order, each unit
// whose batch is used up gets the next `batch` rays of the stream. A unit
// thus takes rays as fast as its slots free up (no unit waits while rays
// remain), and consecutive rays, which are coherent, go to the same unit and
// its L1. Only refill() changes what other units see: the units themselves
// may run on threads of their own. (Here, below the driver and the SystemC
// models, because every model of a chip reads it.)
class Dispatcher {
 public:
  Dispatcher(size_t rays, int units, int batch) : rays_(rays), batch_(size_t(batch)), held_(size_t(units)) {}

  // The ray `unit` offers next, if it holds one.
  bool holds(int unit) const { return held_[size_t(unit)].next < held_[size_t(unit)].end; }
  size_t next(int unit) const { return held_[size_t(unit)].next; }
  // The unit took its ray.
  void taken(int unit) { ++held_[size_t(unit)].next; }
  // The end of a cycle: every unit with none left gets a batch.
  void refill() {
    for (Batch& b : held_) {
      if (b.next < b.end || handed_ == rays_) continue;
      b.next = handed_;
      b.end = std::min(rays_, handed_ + batch_);
      handed_ = b.end;
    }
  }

 private:
  struct Batch {
    size_t next = 0, end = 0;
  };
  size_t rays_, batch_, handed_ = 0;
  std::vector<Batch> held_;
};

}  // namespace lancer
