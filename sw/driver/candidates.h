#pragma once

#include "driver/isect_job.h"
#include "ref/bvh.h"

namespace lancer {

// The reference BVH as the host-side traversal of `--accel bvh`: every triangle in
// every leaf whose box, grown by `margin` scene units on each side, the ray
// touches. No culling by hits: the float hit may not be the fixed-point one, so
// the hardware gets every triangle it could possibly hit.
CandidateSource bvhCandidates(const Bvh& bvh, float margin);

}  // namespace lancer
