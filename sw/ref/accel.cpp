#include "ref/accel.h"

#include <fmt/format.h>

#include "common/error.h"

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

}  // namespace lancer
