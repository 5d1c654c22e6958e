#include "ref/accel.h"

#include <fmt/format.h>

#include "common/error.h"
#include "oracle/embree_accel.h"
#include "ref/bvh.h"
#include "ref/grid.h"
#include "ref/octree.h"

namespace lancer {

std::string_view toString(AccelKind kind) {
  switch (kind) {
    case AccelKind::Grid: return "grid";
    case AccelKind::Octree: return "octree";
    case AccelKind::Bvh: return "bvh";
    case AccelKind::Embree: return "embree";
  }
  return "?";
}

AccelKind parseAccelKind(std::string_view name) {
  for (AccelKind kind : {AccelKind::Grid, AccelKind::Octree, AccelKind::Bvh, AccelKind::Embree}) {
    if (toString(kind) == name) return kind;
  }
  throw InputError(fmt::format("unknown acceleration structure '{}' (expected grid, octree, bvh or embree)", name));
}

std::unique_ptr<Accel> makeAccel(AccelKind kind, const Scene& scene, const AccelOptions& options) {
  switch (kind) {
    case AccelKind::Grid: return std::make_unique<UniformGrid>(scene, options);
    case AccelKind::Octree: return std::make_unique<Octree>(scene, options);
    case AccelKind::Bvh: return std::make_unique<Bvh>(scene, options);
    case AccelKind::Embree: return std::make_unique<EmbreeAccel>(scene);
  }
  throw InputError("unknown acceleration structure");
}

}  // namespace lancer
