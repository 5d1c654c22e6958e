#pragma once

#include <memory>

#include "ref/accel.h"
#include "scene/scene.h"

namespace lancer {

// Builds the structure of `kind` over `scene` (which must outlive it): the
// reference's grid, octree and BVH, or the Embree oracle. It lives here, above
// both, so that the reference does not depend on the oracle that checks it.
// Throws InputError on impossible options.
std::unique_ptr<Accel> makeAccel(AccelKind kind, const Scene& scene,
                                 const AccelOptions& options = {});
std::unique_ptr<Accel> makeAccel(AccelKind, Scene&&, const AccelOptions& = {}) = delete;

}  // namespace lancer
