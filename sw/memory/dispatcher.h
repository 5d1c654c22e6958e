#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "memory/ray_queues.h"

namespace lancer {

// The dispatcher: every unit holds a batch of rays (segment ids: a ray's
// first walk is its index; a resumed walk gets a new id) to offer, one at a
// time; at the end of each cycle, in unit order, each unit whose batch is used
// up gets the next batch of up to `batch`. A unit thus takes rays as fast as
// its slots free up. Two sources:
//   fifo      consecutive rays of the stream, which are coherent, to the same
//             unit and its L1 (the sorted schedule orders the stream first);
//   treelet   the ray queues (memory/ray_queues.h): the rays of one treelet
//             block at a time, each offered once its record has been read.
// Only refill() changes what other units see: the units themselves may run on
// threads of their own. (Here, below the driver and the SystemC models,
// because every model of a chip reads it.)
class Dispatcher {
 public:
  // fifo over `rays` rays.
  Dispatcher(size_t rays, int units, int batch) : rays_(rays), batch_(size_t(batch)), held_(size_t(units)) {}
  // treelet: the ray queues hand the batches out.
  void useQueues(std::unique_ptr<mem::RayQueues> queues) { queues_ = std::move(queues); }
  mem::RayQueues* queues() const { return queues_.get(); }

  // The ray `unit` offers next, if it holds one ready in cycle `now`.
  bool holds(int unit, uint64_t now) const {
    const std::deque<mem::RayQueues::Handed>& h = held_[size_t(unit)];
    return !h.empty() && h.front().readyAt <= now;
  }
  size_t next(int unit) const { return held_[size_t(unit)].front().segment; }
  // The unit took its ray.
  void taken(int unit) { held_[size_t(unit)].pop_front(); }
  // The end of a cycle: every unit with none left gets a batch.
  void refill() {
    for (std::deque<mem::RayQueues::Handed>& h : held_) {
      if (!h.empty()) continue;
      if (queues_) {
        queues_->handOut(batch_, handed_);
        h.assign(handed_.begin(), handed_.end());
      } else {
        const size_t end = std::min(rays_, next_ + batch_);
        for (; next_ < end; ++next_) h.push_back({next_, 0});
      }
    }
  }

 private:
  size_t rays_, batch_, next_ = 0;
  std::vector<std::deque<mem::RayQueues::Handed>> held_;
  std::unique_ptr<mem::RayQueues> queues_;
  std::vector<mem::RayQueues::Handed> handed_;
};

}  // namespace lancer
