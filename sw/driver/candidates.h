#pragma once

#include "driver/isect_job.h"
#include "oracle/exact.h"
#include "ref/bvh.h"

namespace lancer {

// The reference BVH as the host-side traversal of `--accel isect`: every triangle in
// every leaf whose box, grown by `margin` scene units on each side, the ray
// touches. No culling by hits: the float hit may not be the fixed-point one, so
// the hardware gets every triangle it could possibly hit.
CandidateSource bvhCandidates(const Bvh& bvh, float margin);

// The exact arbiter's culling (oracle/exact.h) from the same BVH: boxes grown by
// a margin far above the double slab test's rounding (2^-30 of the scene's
// largest coordinate), so every triangle a ray meets exactly is among them.
TriangleCandidates exactCandidates(const Bvh& bvh, const Aabb& sceneBounds);

}  // namespace lancer
