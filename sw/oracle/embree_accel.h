#pragma once

#include <embree3/rtcore.h>

#include "ref/accel.h"

namespace lancer {

// Embree 3 behind the Accel interface: the independent oracle the reference is
// checked against, and the speed yardstick of `lancer bench`. Robust mode (no
// culling, watertight-leaning traversal), one thread, so the comparison is fair
// to the single-threaded reference.
class EmbreeAccel final : public Accel {
 public:
  explicit EmbreeAccel(const Scene& scene);
  ~EmbreeAccel() override;
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  std::string_view name() const override { return "embree"; }
  std::optional<Hit> intersect(const Ray& ray, TraversalStats* stats = nullptr) const override;
  bool intersectP(const Ray& ray) const override;

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace lancer
