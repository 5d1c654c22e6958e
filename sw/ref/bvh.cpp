#include "ref/bvh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>

#include <fmt/format.h>

#include "common/error.h"
#include "common/sah.h"
#include "ref/primitive.h"

namespace lancer {

namespace {

// pbrt's gamma(n): bound on the relative error of n float roundings.
constexpr float gamma(int n) {
  constexpr float kUnitRoundoff = 0.5f * std::numeric_limits<float>::epsilon();
  return (n * kUnitRoundoff) / (1.0f - n * kUnitRoundoff);
}

// pbrt-v3/v4's growth of a slab's far distance: the three roundings of
// (plane - origin) * (1 / dir) stay within gamma(3) on each side, so a box the
// ray touches is never culled because of them.
constexpr float kFarGrowth = 1.0f + 2.0f * gamma(3);

// Absolute slack added around every box, relative to the distance S from the ray
// origin to the farthest corner of the scene. The watertight test does not decide
// the exact ray: its shear and edge functions round at about 10 ulps of S, so it
// may accept a triangle the exact ray passes just outside of, at a t whose point
// lies just outside the box. 2^-16 S (256 unit roundoffs, ~25x that error)
// covers it with room for the t error of grazing hits down to ~2 degrees
// (docs/bvh.md); it costs nothing measurable, where 2^-12 costs 18%.
constexpr float kRelativeSlack = 0x1p-16f;
// Floor of the slack so subnormal rounding near a zero S cannot cull either.
constexpr float kAbsoluteSlack = 1e-30f;

// Fast path: float slab test for rays with no zero or tiny direction component.
// The slack is folded into two shifted origins, rounded outwards, so the test
// costs the same as a plain slab test:
//   t(lo - delta) = (lo - (o + delta)) / d,   t(hi + delta) = (hi - (o - delta)) / d.
struct FastSlab {
  std::array<float, 3> oPlus, oMinus, inv;

  // True if the inflated box overlaps the ray in [0, tLimit].
  bool overlaps(const BvhNode& n, float tLimit) const {
    const float t0x = (n.lo.x - oPlus[0]) * inv[0];
    const float t1x = (n.hi.x - oMinus[0]) * inv[0];
    const float t0y = (n.lo.y - oPlus[1]) * inv[1];
    const float t1y = (n.hi.y - oMinus[1]) * inv[1];
    const float t0z = (n.lo.z - oPlus[2]) * inv[2];
    const float t1z = (n.hi.z - oMinus[2]) * inv[2];
    // Entry is the last slab entered, exit the first left. No NaN can occur:
    // every factor is finite and inv is never zero.
    const float tNear = std::max(std::max(std::min(t0x, t1x), std::min(t0y, t1y)),
                                 std::max(std::min(t0z, t1z), 0.0f));
    const float tFar = std::min(std::min(std::max(t0x, t1x), std::max(t0y, t1y)),
                                std::max(t0z, t1z)) * kFarGrowth;
    // `<=`: a box entered exactly at the closest hit's t may still hold a tie
    // that the lower triangle id wins.
    return tNear <= std::min(tFar, tLimit);
  }
};

// Exact path, in double, for rays with a zero (0 or -0.0) or tiny direction
// component. A zero component is decided by comparing the origin with the slab
// instead of multiplying by an infinite reciprocal, so an origin lying on a slab
// plane gives no 0 * inf = NaN. Doubles hold every float difference and product
// here without overflow.
struct ExactSlab {
  std::array<double, 3> origin, inv;
  std::array<bool, 3> zero;
  double delta;

  bool overlaps(const BvhNode& n, float tLimit) const {
    double tNear = 0.0, tFar = tLimit;
    for (int a = 0; a < 3; ++a) {
      const double lo = double(n.lo[a]) - delta, hi = double(n.hi[a]) + delta;
      if (zero[a]) {
        // The ray stays in the plane x_a = origin: inside the slab for all t or never.
        if (origin[a] < lo || origin[a] > hi) return false;
        continue;
      }
      double t0 = (lo - origin[a]) * inv[a];
      double t1 = (hi - origin[a]) * inv[a];
      if (t0 > t1) std::swap(t0, t1);
      tNear = std::max(tNear, t0);
      tFar = std::min(tFar, t1 * double(kFarGrowth));
    }
    return tNear <= tFar;
  }
};

// The neighbouring floats towards +inf and -inf (finite, non-NaN inputs), inline
// because std::nextafter is a library call.
float nextUp(float x) {
  if (x == 0.0f) return std::numeric_limits<float>::denorm_min();
  const uint32_t bits = std::bit_cast<uint32_t>(x);
  return std::bit_cast<float>(x > 0.0f ? bits + 1 : bits - 1);
}
float nextDown(float x) { return -nextUp(-x); }

}  // namespace

Bvh::Bvh(const Scene& scene, const AccelOptions& options)
    : leafSize_(options.bvhLeafSize), triangleCount_(uint32_t(scene.triangles.size())) {
  if (leafSize_ < 1 || leafSize_ > kMaxLeafSize) {
    throw InputError(fmt::format("BVH leaf size {} must lie in 1..{}", leafSize_, kMaxLeafSize));
  }
  const size_t n = scene.primitiveCount();
  if (n == 0) return;  // no nodes: every query misses
  if (n > std::numeric_limits<uint32_t>::max()) throw InputError("bvh: more than 2^32 - 1 primitives");
  // Every primitive by its box: a triangle's vertices', a quadric's Quadric::bounds().
  std::vector<Aabb> boxes(n);
  for (size_t i = 0; i < n; ++i) {
    boxes[i] = primitiveBounds(scene, uint32_t(i));
    bounds_.extend(boxes[i]);
  }
  // A step is an out-of-line call returning std::optional, comparatively cheap
  // against a triangle test: traversal cost 1.
  const SahTree tree = buildSah(boxes, SahOptions{.leafSize = leafSize_, .maxDepth = kMaxDepth});
  depth_ = tree.depth;
  leafCount_ = tree.leaves;
  primIds_ = tree.order;
  nodes_.resize(tree.nodes.size());
  for (size_t i = 0; i < tree.nodes.size(); ++i) {
    const SahNode& from = tree.nodes[i];
    BvhNode& node = nodes_[i];
    node.lo = from.box.lo;
    node.hi = from.box.hi;
    if (from.leaf) {
      node.index = from.begin;
      node.count = uint16_t(from.count());
    } else {
      node.index = from.right;
      node.axis = from.axis;
    }
  }
  // A quadric's slot in the leaf-ordered triangles is a placeholder: the
  // traversal tests it by its id, against quadrics_.
  triangles_.reserve(n);
  for (uint32_t id : primIds_) triangles_.push_back(id < triangleCount_ ? scene.triangles[id] : Triangle{});
  quadrics_.reserve(scene.quadrics.size());
  for (const Quadric& q : scene.quadrics) quadrics_.push_back(QuadricShape::of(q));
}

template <bool kAnyHit, bool kCount, bool kQuadrics, typename Slab>
std::optional<Hit> Bvh::traverse(const Ray& ray, const Slab& slab, TraversalStats* stats) const {
  const WatertightRay wray(ray);
  // Descend into the child on the near side of the split plane first, so the
  // closest hit is usually found early and prunes the far child.
  const std::array<bool, 3> negative = {ray.dir.x < 0.0f, ray.dir.y < 0.0f, ray.dir.z < 0.0f};
  const BvhNode* nodes = nodes_.data();
  const Triangle* triangles = triangles_.data();
  std::optional<Hit> best;
  float tLimit = ray.tMax;
  uint64_t visited = 0, tests = 0, quadricTests = 0;
  // The primitive at leaf slot i: a triangle (the only kind without kQuadrics)
  // or a quadric, by its id.
  const auto testSlot = [&](uint32_t i) -> std::optional<Hit> {
    if constexpr (kQuadrics) {
      const uint32_t id = primIds_[i];
      if (id >= triangleCount_) {
        if constexpr (kCount) ++quadricTests;
        return intersectQuadricHit(ray, quadrics_[id - triangleCount_], id);
      }
      if constexpr (kCount) ++tests;
    }
    return intersectTriangle(wray, triangles[i], primIds_[i]);
  };

  std::array<uint32_t, kMaxDepth> stack;  // depth-first: at most one entry per level
  int top = 0;
  uint32_t current = 0;
  for (;;) {
    const BvhNode& node = nodes[current];
    if (slab.overlaps(node, tLimit)) {
      if constexpr (kCount) ++visited;
      if (!node.isLeaf()) {
        if (negative[node.axis]) {
          stack[top++] = current + 1;
          current = node.index;
        } else {
          stack[top++] = node.index;
          current = current + 1;
        }
        continue;
      }
      if constexpr (kCount && !kQuadrics) tests += node.count;
      for (uint32_t i = node.index, e = node.index + node.count; i < e; ++i) {
        if (auto hit = testSlot(i)) {
          if constexpr (kAnyHit) return hit;
          keepCloser(best, *hit);
          tLimit = best->t;
        }
      }
    }
    if (top == 0) break;
    current = stack[--top];
  }
  if constexpr (kCount) {
    stats->nodesVisited += visited;
    stats->triangleTests += tests;
    stats->quadricTests += quadricTests;
  }
  return best;
}

template <bool kAnyHit, bool kQuadrics>
std::optional<Hit> Bvh::dispatch(const Ray& ray, TraversalStats* stats) const {
  // Rays the watertight test has no answer for (NaN or infinite components, a
  // zero direction) hit nothing; callers should reject them as bad input.
  if (nodes_.empty() || !allFinite(ray.origin) || !allFinite(ray.dir) ||
      ray.dir == glm::vec3(0.0f) || std::isnan(ray.tMax)) {
    return std::nullopt;
  }
  // S: distance (max norm) from the origin to the farthest corner of the scene,
  // which bounds |v - o| for every vertex v and so every rounding error below.
  const glm::vec3 far = glm::max(glm::abs(bounds_.lo - ray.origin), glm::abs(bounds_.hi - ray.origin));
  const float s = std::max(far.x, std::max(far.y, far.z));
  const float delta = kRelativeSlack * s + kAbsoluteSlack;

  bool fast = true;
  for (int a = 0; a < 3; ++a) {
    // The products (plane - o) * inv stay below 2 (S + delta) |inv|; keep them
    // far from overflow, and send zero, subnormal or tiny components to the
    // exact path.
    const float inv = 1.0f / ray.dir[a];
    fast = fast && ray.dir[a] != 0.0f && std::abs(inv) * (4.0f * (s + delta)) < 1e37f;
  }
  if (fast) {
    FastSlab slab;
    for (int a = 0; a < 3; ++a) {
      slab.oPlus[a] = nextUp(ray.origin[a] + delta);
      slab.oMinus[a] = nextDown(ray.origin[a] - delta);
      slab.inv[a] = 1.0f / ray.dir[a];
    }
    return stats ? traverse<kAnyHit, true, kQuadrics>(ray, slab, stats)
                 : traverse<kAnyHit, false, kQuadrics>(ray, slab, stats);
  }
  ExactSlab slab;
  slab.delta = 2.0 * double(delta);  // outward margin for the double roundings too
  for (int a = 0; a < 3; ++a) {
    slab.origin[a] = ray.origin[a];
    slab.zero[a] = ray.dir[a] == 0.0f;  // true for -0.0 as well
    slab.inv[a] = slab.zero[a] ? 0.0 : 1.0 / double(ray.dir[a]);
  }
  return stats ? traverse<kAnyHit, true, kQuadrics>(ray, slab, stats)
               : traverse<kAnyHit, false, kQuadrics>(ray, slab, stats);
}

// A scene without quadrics runs the triangle-only loop.
std::optional<Hit> Bvh::intersect(const Ray& ray, TraversalStats* stats) const {
  return quadrics_.empty() ? dispatch<false, false>(ray, stats) : dispatch<false, true>(ray, stats);
}

bool Bvh::intersectP(const Ray& ray) const {
  return (quadrics_.empty() ? dispatch<true, false>(ray, nullptr) : dispatch<true, true>(ray, nullptr)).has_value();
}

}  // namespace lancer
