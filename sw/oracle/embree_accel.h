#pragma once

#include <vector>

#include <embree3/rtcore.h>

#include "ref/accel.h"

namespace lancer {

// Embree 3 behind the Accel interface: the independent oracle the reference is
// checked against, and the speed yardstick of `lancer bench`. Robust mode (no
// culling, watertight-leaning traversal), one thread, so the comparison is fair
// to the single-threaded reference. A scene's quadrics (issue #40) are an
// Embree user geometry whose callbacks run the float reference's test
// (ref/quadric.h; Embree 3's own spheres and round curves do not trace NFF's
// open cones); their ids follow the triangles', as in Scene.
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
  uint32_t triangleCount_ = 0;
  unsigned quadricGeometry_ = RTC_INVALID_GEOMETRY_ID;
  std::vector<Quadric> quadrics_;  // the scene's, for the user geometry's callbacks
};

}  // namespace lancer
