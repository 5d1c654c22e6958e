#include "oracle/make_accel.h"

#include "common/error.h"
#include "oracle/embree_accel.h"
#include "ref/bvh.h"
#include "ref/grid.h"
#include "ref/octree.h"

namespace lancer {

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
