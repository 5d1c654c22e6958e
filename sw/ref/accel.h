#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "common/accel_options.h"
#include "common/ray.h"
#include "scene/scene.h"

namespace lancer {

// Named statistics of one or more queries (pbrt-style counters, not prints).
struct TraversalStats {
  uint64_t nodesVisited = 0;   // BVH/octree nodes or grid voxels entered
  uint64_t triangleTests = 0;  // ray-triangle tests performed
  uint64_t quadricTests = 0;   // ray-quadric tests performed (native spheres and cones)

  TraversalStats& operator+=(const TraversalStats& o) {
    nodesVisited += o.nodesVisited;
    triangleTests += o.triangleTests;
    quadricTests += o.quadricTests;
    return *this;
  }
};

// The query interface every acceleration structure implements: the reference
// grid, octree and BVH, and the Embree oracle. Each is built over every
// primitive of its scene, triangles and native quadrics, and reports hits in
// the scene's one id space (scene.h). Implementations are immutable
// after construction, so queries may run concurrently.
class Accel {
 public:
  virtual ~Accel() = default;
  virtual std::string_view name() const = 0;
  // Closest hit in (0, ray.tMax], ties broken by closerHit(); nullopt on a miss.
  virtual std::optional<Hit> intersect(const Ray& ray, TraversalStats* stats = nullptr) const = 0;
  // Any hit in (0, ray.tMax]: the shadow-ray query.
  virtual bool intersectP(const Ray& ray) const = 0;
};

enum class AccelKind { Grid, Octree, Bvh, Embree };

std::string_view toString(AccelKind kind);
// Throws InputError for an unknown name.
AccelKind parseAccelKind(std::string_view name);

// How the float structures take an AccelOptions field that a unit's build
// option also sets (golden/unit.h, BuildOption::shapesReference): what `lancer
// render` and `lancer trace` say of its flag, and the largest value they take
// (the float grid's --grid-res counts voxels along the longest axis, up to
// 1024; the unit's, cells on every axis).
struct ReferenceBuildOption {
  int AccelOptions::*field;
  std::string help;
  int max;  // INT_MAX: no limit
};
// The entry of `field`; nullptr if no float structure reads it.
const ReferenceBuildOption* findReferenceBuildOption(int AccelOptions::*field);

}  // namespace lancer
