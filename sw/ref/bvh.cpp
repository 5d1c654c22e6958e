#include "ref/bvh.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>

#include <fmt/format.h>

#include "common/error.h"
#include "ref/triangle.h"

namespace lancer {

namespace {

// SAH cost of one node step relative to one ray-triangle test. The triangle test
// is an out-of-line call returning std::optional, so a step is comparatively cheap.
constexpr float kTraversalCost = 1.0f;

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

int ceilLog2(size_t n) { return n <= 1 ? 0 : int(std::bit_width(n - 1)); }

}  // namespace

struct Bvh::BuildPrim {
  Aabb box;
  glm::vec3 centroid;
  uint32_t index;
};

Bvh::Bvh(const Scene& scene, const AccelOptions& options) : leafSize_(options.bvhLeafSize) {
  if (leafSize_ < 1 || leafSize_ > kMaxLeafSize) {
    throw InputError(fmt::format("BVH leaf size {} must lie in 1..{}", leafSize_, kMaxLeafSize));
  }
  const size_t n = scene.triangles.size();
  if (n == 0) return;  // no nodes: every query misses
  std::vector<BuildPrim> prims(n);
  for (size_t i = 0; i < n; ++i) {
    prims[i].box = scene.triangles[i].bounds();
    prims[i].centroid = prims[i].box.center();
    prims[i].index = uint32_t(i);
    bounds_.extend(prims[i].box);
  }
  nodes_.reserve(2 * n);
  triangles_.reserve(n);
  primIds_.reserve(n);
  build(prims, 0, n, 1);
  for (uint32_t id : primIds_) triangles_.push_back(scene.triangles[id]);
}

// Builds the subtree over prims[begin, end) at tree level `depth` (root = 1) and
// returns its node index. Children are emitted right after their parent (left
// subtree first), which gives the depth-first layout.
uint32_t Bvh::build(std::vector<BuildPrim>& prims, size_t begin, size_t end, int depth) {
  const uint32_t nodeIndex = uint32_t(nodes_.size());
  nodes_.emplace_back();
  depth_ = std::max(depth_, depth);
  const size_t n = end - begin;

  Aabb box, centroids;
  for (size_t i = begin; i < end; ++i) {
    box.extend(prims[i].box);
    centroids.extend(prims[i].centroid);
  }
  nodes_[nodeIndex].lo = box.lo;
  nodes_[nodeIndex].hi = box.hi;

  auto makeLeaf = [&] {
    BvhNode& node = nodes_[nodeIndex];
    node.index = uint32_t(primIds_.size());
    node.count = uint16_t(n);
    for (size_t i = begin; i < end; ++i) primIds_.push_back(prims[i].index);
    ++leafCount_;
    return nodeIndex;
  };
  if (n == 1) return makeLeaf();

  // Binned SAH over the centroid bounds. Costs are kept multiplied by the node's
  // area (no division), so flat or point-like nodes compare without NaN.
  const float area = box.surfaceArea();
  const float leafCost = float(n) * area;
  int bestAxis = -1, bestBin = 0;
  float bestCost = std::numeric_limits<float>::infinity();
  auto binOf = [&](const glm::vec3& c, int axis, float scale) {
    const int b = int((c[axis] - centroids.lo[axis]) * scale);
    return std::clamp(b, 0, kSahBins - 1);
  };
  for (int axis = 0; axis < 3; ++axis) {
    const float extent = centroids.hi[axis] - centroids.lo[axis];
    if (!(extent > 0.0f)) continue;
    const float scale = float(kSahBins) / extent;
    std::array<Aabb, kSahBins> binBox;
    std::array<size_t, kSahBins> binCount{};
    for (size_t i = begin; i < end; ++i) {
      const int b = binOf(prims[i].centroid, axis, scale);
      ++binCount[b];
      binBox[b].extend(prims[i].box);
    }
    // Sweep from the right to get the area and count right of each split plane.
    std::array<float, kSahBins> rightArea;
    std::array<size_t, kSahBins> rightCount;
    Aabb acc;
    size_t count = 0;
    for (int b = kSahBins - 1; b > 0; --b) {
      acc.extend(binBox[b]);
      count += binCount[b];
      rightArea[b] = acc.empty() ? 0.0f : acc.surfaceArea();
      rightCount[b] = count;
    }
    acc = Aabb{};
    count = 0;
    for (int b = 0; b < kSahBins - 1; ++b) {  // split between bin b and b + 1
      acc.extend(binBox[b]);
      count += binCount[b];
      if (count == 0 || rightCount[b + 1] == 0) continue;
      const float cost = kTraversalCost * area + float(count) * acc.surfaceArea() +
                         float(rightCount[b + 1]) * rightArea[b + 1];
      if (cost < bestCost) {
        bestCost = cost;
        bestAxis = axis;
        bestBin = b;
      }
    }
  }

  if (n <= size_t(leafSize_) && (bestAxis < 0 || leafCost <= bestCost)) return makeLeaf();

  // Depth guard: an SAH split may peel off one triangle per level. Once the
  // remaining levels could exceed kMaxDepth, halve instead, which needs only
  // ceil(log2 n) more levels; SAH keeps the first 30 levels at least.
  const bool forceMedian = depth + 1 + ceilLog2(n) > kMaxDepth;
  size_t mid;
  int splitAxis;
  if (bestAxis < 0 || forceMedian) {
    // Median split: also the fallback when every centroid coincides.
    const glm::vec3 d = centroids.diagonal();
    splitAxis = (d.x >= d.y && d.x >= d.z) ? 0 : (d.y >= d.z ? 1 : 2);
    mid = begin + n / 2;
    std::nth_element(prims.begin() + ptrdiff_t(begin), prims.begin() + ptrdiff_t(mid),
                     prims.begin() + ptrdiff_t(end), [splitAxis](const BuildPrim& a, const BuildPrim& b) {
                       return a.centroid[splitAxis] < b.centroid[splitAxis];
                     });
  } else {
    splitAxis = bestAxis;
    const float scale = float(kSahBins) / (centroids.hi[bestAxis] - centroids.lo[bestAxis]);
    auto it = std::partition(prims.begin() + ptrdiff_t(begin), prims.begin() + ptrdiff_t(end),
                             [&](const BuildPrim& p) { return binOf(p.centroid, bestAxis, scale) <= bestBin; });
    mid = size_t(it - prims.begin());
  }
  assert(mid > begin && mid < end);

  build(prims, begin, mid, depth + 1);
  const uint32_t right = build(prims, mid, end, depth + 1);
  nodes_[nodeIndex].index = right;
  nodes_[nodeIndex].axis = uint8_t(splitAxis);
  return nodeIndex;
}

template <bool kAnyHit, bool kCount, typename Slab>
std::optional<Hit> Bvh::traverse(const Ray& ray, const Slab& slab, TraversalStats* stats) const {
  const WatertightRay wray(ray);
  // Descend into the child on the near side of the split plane first, so the
  // closest hit is usually found early and prunes the far child.
  const std::array<bool, 3> negative = {ray.dir.x < 0.0f, ray.dir.y < 0.0f, ray.dir.z < 0.0f};
  const BvhNode* nodes = nodes_.data();
  const Triangle* triangles = triangles_.data();
  std::optional<Hit> best;
  float tLimit = ray.tMax;
  uint64_t visited = 0, tests = 0;

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
      if constexpr (kCount) tests += node.count;
      for (uint32_t i = node.index, e = node.index + node.count; i < e; ++i) {
        if (auto hit = intersectTriangle(wray, triangles[i], primIds_[i])) {
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
  }
  return best;
}

template <bool kAnyHit>
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
    return stats ? traverse<kAnyHit, true>(ray, slab, stats) : traverse<kAnyHit, false>(ray, slab, stats);
  }
  ExactSlab slab;
  slab.delta = 2.0 * double(delta);  // outward margin for the double roundings too
  for (int a = 0; a < 3; ++a) {
    slab.origin[a] = ray.origin[a];
    slab.zero[a] = ray.dir[a] == 0.0f;  // true for -0.0 as well
    slab.inv[a] = slab.zero[a] ? 0.0 : 1.0 / double(ray.dir[a]);
  }
  return stats ? traverse<kAnyHit, true>(ray, slab, stats) : traverse<kAnyHit, false>(ray, slab, stats);
}

std::optional<Hit> Bvh::intersect(const Ray& ray, TraversalStats* stats) const {
  return dispatch<false>(ray, stats);
}

bool Bvh::intersectP(const Ray& ray) const { return dispatch<true>(ray, nullptr).has_value(); }

}  // namespace lancer
