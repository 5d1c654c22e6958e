#include "ref/octree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "common/error.h"
#include "ref/grid.h"  // binningEpsilon, TriangleMailbox
#include "ref/primitive.h"

namespace lancer {

namespace {

// The split plane of [lo, hi]. The builder and the traversal of rays parallel to
// an axis both use this one expression, so they agree on its bits.
float midpoint(float lo, float hi) { return 0.5f * (lo + hi); }

// Child c's box: bit 4 selects the upper x half, bit 2 upper y, bit 1 upper z.
constexpr int kAxisBit[3] = {4, 2, 1};

Aabb childBox(const Aabb& box, int c) {
  Aabb child;
  for (int a = 0; a < 3; ++a) {
    const float mid = midpoint(box.lo[a], box.hi[a]);
    const bool upper = c & kAxisBit[a];
    child.lo[a] = upper ? mid : box.lo[a];
    child.hi[a] = upper ? box.hi[a] : mid;
  }
  return child;
}

// Revelles et al., Table 3 (new_node): the child entered after child c when it is
// left through its x, y or z exit plane; 8 means the ray leaves the parent.
// clang-format off
constexpr uint8_t kNextChild[8][3] = {
    {4, 2, 1}, {5, 3, 8}, {6, 8, 3}, {7, 8, 8},
    {8, 6, 5}, {8, 7, 8}, {8, 8, 7}, {8, 8, 8},
};
// clang-format on

// Revelles et al., Tables 1 and 2 (first_node): the entry plane is the axis of
// the largest t0; the child's bit on each other axis is set when the ray crosses
// that axis's mid-plane before entering the node. Ties follow the paper's code.
int firstChild(const double t0[3], const double tm[3]) {
  int c = 0;
  if (t0[0] > t0[1] && t0[0] > t0[2]) {  // entry through a YZ face
    if (tm[1] < t0[0]) c |= 2;
    if (tm[2] < t0[0]) c |= 1;
  } else if (!(t0[0] > t0[1]) && t0[1] > t0[2]) {  // XZ face
    if (tm[0] < t0[1]) c |= 4;
    if (tm[2] < t0[1]) c |= 1;
  } else {  // XY face
    if (tm[0] < t0[2]) c |= 4;
    if (tm[1] < t0[2]) c |= 2;
  }
  return c;
}

// The exit plane of a child: the axis of the smallest t1, ties as in the paper's
// new_node (x only if strictly first, then y, else z).
int exitAxis(const double t1[3]) {
  if (t1[0] < t1[1]) return t1[0] < t1[2] ? 0 : 2;
  return t1[1] < t1[2] ? 1 : 2;
}

}  // namespace

Octree::Octree(const Scene& scene, const AccelOptions& options) : scene_(scene) {
  if (options.octreeMaxDepth < 0 || options.octreeMaxDepth > kMaxOctreeDepth) {
    throw InputError(
        fmt::format("octree max depth {} is out of range (expected 1..{}, or 0 for the default {})",
                    options.octreeMaxDepth, kMaxOctreeDepth, kDefaultMaxDepth));
  }
  if (options.octreeLeafSize < 0) {
    throw InputError(fmt::format(
        "octree leaf size {} is out of range (expected a positive triangle count, or 0 for "
        "the default {})",
        options.octreeLeafSize, kDefaultLeafSize));
  }
  if (options.octreeMaxDepth > 0) maxDepth_ = options.octreeMaxDepth;
  if (options.octreeLeafSize > 0) leafSize_ = options.octreeLeafSize;
  const size_t primitives = scene.primitiveCount();
  if (primitives == 0) return;  // no nodes; every ray misses

  // The root box and every primitive's box (a quadric's Quadric::bounds()) are
  // grown by the same epsilon as the grid's, for the same reason: a primitive
  // within rounding of a split plane is listed on both sides of it.
  const auto [box, eps] = binningBox(scene, "octree");
  bounds_ = box;
  std::vector<Aabb> grown(primitives);
  std::vector<uint32_t> all(primitives);
  for (size_t i = 0; i < primitives; ++i) {
    const Aabb b = primitiveBounds(scene, uint32_t(i));
    grown[i] = Aabb{b.lo - eps, b.hi + eps};
    all[i] = static_cast<uint32_t>(i);
  }
  nodes_.emplace_back();
  build(0, bounds_, std::move(all), 0, grown);
}

void Octree::build(uint32_t node, const Aabb& box, std::vector<uint32_t> tris, int depth,
                   const std::vector<Aabb>& grown) {
  depth_ = std::max(depth_, depth);
  const auto makeLeaf = [&] {
    if (triIndices_.size() + tris.size() > std::numeric_limits<uint32_t>::max()) {
      throw InputError("octree needs more than 2^32 triangle references; lower the max depth");
    }
    nodes_[node] =
        Node{static_cast<uint32_t>(triIndices_.size()), static_cast<uint32_t>(tris.size())};
    triIndices_.insert(triIndices_.end(), tris.begin(), tris.end());
  };
  if (tris.size() <= size_t(leafSize_) || depth >= maxDepth_) return makeLeaf();

  // Step 1: distribute the triangles over the eight children by grown box overlap
  // (closed intervals, so a box touching a split plane goes to both sides). Every
  // triangle here overlaps `box`, so overlapping a child reduces to one compare
  // per axis against the mid-plane: lo <= mid for the lower half, hi >= mid for
  // the upper, which is exactly Aabb::overlaps() with the child's box.
  std::array<Aabb, 8> boxes;
  for (int c = 0; c < 8; ++c) boxes[c] = childBox(box, c);
  const glm::vec3 mid = boxes[0].hi;
  std::array<std::vector<uint32_t>, 8> lists;
  size_t references = 0;
  for (uint32_t t : tris) {
    const Aabb& g = grown[t];
    int sides[3];  // bit 0: overlaps the lower half, bit 1: the upper half
    for (int a = 0; a < 3; ++a)
      sides[a] = (g.lo[a] <= mid[a] ? 1 : 0) | (g.hi[a] >= mid[a] ? 2 : 0);
    for (int c = 0; c < 8; ++c) {
      if ((sides[0] & (c & 4 ? 2 : 1)) && (sides[1] & (c & 2 ? 2 : 1)) &&
          (sides[2] & (c & 1 ? 2 : 1))) {
        lists[c].push_back(t);
        ++references;
      }
    }
  }
  // Step 2: split only if it is expected to save triangle tests (a one-level
  // surface-area heuristic). A child has 1/4 of its parent's surface area, so a
  // ray through the node enters it with probability 1/4; with a traversal step
  // costing about one test, splitting n triangles into children holding
  // sum(n_c) references pays when sum(n_c) / 4 + 1 < n. This stops where
  // children would duplicate rather than separate triangles: along an edge or
  // at a vertex shared by more than leafSize triangles (which would otherwise
  // refine to maxDepth along every edge of the mesh), and in cells already
  // smaller than the epsilon. A tight cluster in a large node still splits, since
  // it lands in one child (sum(n_c) = n).
  if (references >= 4 * (tris.size() - 1)) return makeLeaf();

  // Step 3: allocate the eight children together, then recurse (the recursion is
  // at most maxDepth_ <= kMaxOctreeDepth deep).
  if (nodes_.size() + 8 > std::numeric_limits<uint32_t>::max()) {
    throw InputError("octree needs more than 2^32 nodes; lower the max depth");
  }
  const auto base = static_cast<uint32_t>(nodes_.size());
  nodes_.resize(nodes_.size() + 8);
  nodes_[node] = Node{base, kInternal};
  tris = {};  // free the parent's list before descending
  for (int c = 0; c < 8; ++c) build(base + c, boxes[c], std::move(lists[c]), depth + 1, grown);
}

// The traversal is the parametric algorithm of Revelles, Ureña and Lastra (2000),
// with the recursion of proc_subtree unrolled onto an explicit stack: one frame
// per internal node on the current path, so at most maxDepth_ <= kMaxOctreeDepth.
//
// Parameters are doubles: for a tiny direction component the slab parameters of
// a float computation overflow, and 0.5 * (t0 + t1) would then be inf - inf. In
// double, (x - o) / d of floats is finite for every non-zero d.
//
// Why there are no gaps: a child's six parameters are copies of its parent's t0,
// tm and t1, and the next child's entry parameter on the exit axis is the very
// value (the same tm or t1) at which the previous child was left. The children's
// intervals therefore chain from the parent's entry to its exit, and by induction
// the leaves visited cover the ray's whole interval in the root, in order. Where
// the exact mid-plane crossing differs from 0.5 * (t0 + t1) by rounding, the ray
// is within ulps of both children and the grown boxes list nearby triangles in
// both.
template <bool kAnyHit, bool kQuadrics>
std::optional<Hit> Octree::traverse(const Ray& ray, TraversalStats* stats) const {
  if (nodes_.empty()) return std::nullopt;
  const glm::vec3& dir = ray.dir;
  // Not a ray: nothing is hit (see the class comment).
  if (!allFinite(ray.origin) || !allFinite(dir) || std::isnan(ray.tMax)) return std::nullopt;
  if (dir.x == 0.0f && dir.y == 0.0f && dir.z == 0.0f) return std::nullopt;

  // Step 1: the root's slab parameters. A negative component is mirrored: the ray
  // is reflected in the root's mid-plane on that axis, o' = lo + hi - o, d' = -d
  // (not o' = -o, which is the mirror only for a root centred on the origin), so
  // every component of d' is >= 0. Every split is at a midpoint, so the mirror maps
  // the tree onto itself with each node's lower and upper halves on that axis
  // exchanged: where the mirrored ray visits child c, the ray visits c ^ a. A zero
  // component (+0 or -0) is never mirrored: the ray is parallel to that slab,
  // inside it for all t (t0 = -inf, t1 = +inf) or for none. In double, lo + hi - o
  // of floats is exact or within an ulp of a double, far below the epsilon.
  int a = 0;
  bool parallel[3];
  double t0[3], t1[3];
  for (int k = 0; k < 3; ++k) {
    const double lo = bounds_.lo[k], hi = bounds_.hi[k];
    double o = ray.origin[k], d = dir[k];
    parallel[k] = d == 0.0;
    if (parallel[k]) {
      if (o < lo || o > hi) return std::nullopt;
      t0[k] = -std::numeric_limits<double>::infinity();
      t1[k] = std::numeric_limits<double>::infinity();
      continue;
    }
    if (d < 0.0) {
      o = lo + hi - o;
      d = -d;
      a |= kAxisBit[k];
    }
    t0[k] = (lo - o) / d;
    t1[k] = (hi - o) / d;
  }
  const double tMax = ray.tMax;
  if (!(std::max({t0[0], t0[1], t0[2]}) <= std::min({t1[0], t1[1], t1[2]}))) return std::nullopt;

  // Step 2: walk the tree. A frame is one internal node on the current path: its
  // parameters, the next child to visit (mirrored numbering, 8 = done), and, on
  // parallel axes only, the node's extent (where the ray is, not when it crosses).
  struct Frame {
    uint32_t node;
    int next;
    double t0[3], tm[3], t1[3];
    float lo[3], hi[3];
  };
  std::array<Frame, kMaxOctreeDepth + 1> stack;
  int top = -1;
  const WatertightRay wray(ray);
  std::optional<Hit> best;
  TriangleMailbox mailbox;
  bool done = false;

  // proc_subtree of the paper for one node; pushes a frame for an internal node.
  const auto enter = [&](uint32_t node, const double(&n0)[3], const double(&n1)[3],
                         const float(&lo)[3], const float(&hi)[3]) {
    const double tEntry = std::max({n0[0], n0[1], n0[2]});
    const double tExit = std::min({n1[0], n1[1], n1[2]});
    if (tExit < 0.0) return;  // behind the origin; later siblings may still count
    if (tEntry > tMax) {      // this and every later node start beyond tMax
      done = true;
      return;
    }
    if (stats) ++stats->nodesVisited;
    const Node& n = nodes_[node];
    if (n.count != kInternal) {
      for (uint32_t k = n.first; k < n.first + n.count; ++k) {
        const uint32_t prim = triIndices_[k];
        if (mailbox.testedBefore(prim)) continue;  // same ray, same primitive: same answer
        if (auto hit = intersectCounted<kQuadrics>(scene_, wray, ray, prim, stats)) {
          if constexpr (kAnyHit) {
            best = hit;
            done = true;
            return;
          }
          keepCloser(best, *hit);
        }
      }
      // Early termination: a closer (or tied) hit than best would lie within this
      // leaf's interval and so was tested here. A hit beyond tExit may still lose
      // to a triangle in a later leaf.
      if ((best && best->t <= tExit) || tExit >= tMax) done = true;
      return;
    }
    Frame& f = stack[++top];
    f.node = node;
    for (int k = 0; k < 3; ++k) {
      f.t0[k] = n0[k];
      f.t1[k] = n1[k];
      f.lo[k] = lo[k];
      f.hi[k] = hi[k];
      if (!parallel[k]) {
        // The mid-plane parameter from the parent's, with no division.
        f.tm[k] = 0.5 * (n0[k] + n1[k]);
      } else {
        // 0.5 * (-inf + inf) is NaN; instead the ray, which never crosses the
        // mid-plane, is on its lower side for all t (crossing "at +inf") or on its
        // upper side for all t (crossing "at -inf"). A ray in the plane goes up;
        // the grown boxes list the plane's triangles on both sides.
        f.tm[k] = ray.origin[k] < midpoint(lo[k], hi[k]) ? std::numeric_limits<double>::infinity()
                                                         : -std::numeric_limits<double>::infinity();
      }
    }
    f.next = firstChild(f.t0, f.tm);
  };

  const float rootLo[3] = {bounds_.lo.x, bounds_.lo.y, bounds_.lo.z};
  const float rootHi[3] = {bounds_.hi.x, bounds_.hi.y, bounds_.hi.z};
  enter(0, t0, t1, rootLo, rootHi);
  while (top >= 0 && !done) {
    Frame& f = stack[top];
    if (f.next == 8) {
      --top;
      continue;
    }
    // Step 3: the current child's parameters: on each axis the lower half spans
    // [t0, tm] and the upper half [tm, t1] (in mirrored space).
    const int c = f.next;
    double c0[3], c1[3];
    float lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      const bool upper = c & kAxisBit[k];
      c0[k] = upper ? f.tm[k] : f.t0[k];
      c1[k] = upper ? f.t1[k] : f.tm[k];
      lo[k] = f.lo[k];
      hi[k] = f.hi[k];
      if (parallel[k]) (upper ? lo[k] : hi[k]) = midpoint(f.lo[k], f.hi[k]);
    }
    // Step 4: its successor, from its exit plane; then descend into it. The child
    // actually stored is c ^ a, undoing the mirroring.
    f.next = kNextChild[c][exitAxis(c1)];
    enter(nodes_[f.node].first + uint32_t(c ^ a), c0, c1, lo, hi);
  }
  return best;
}

std::optional<Hit> Octree::intersect(const Ray& ray, TraversalStats* stats) const {
  return scene_.quadrics.empty() ? traverse<false, false>(ray, stats) : traverse<false, true>(ray, stats);
}

bool Octree::intersectP(const Ray& ray) const {
  return (scene_.quadrics.empty() ? traverse<true, false>(ray, nullptr) : traverse<true, true>(ray, nullptr))
      .has_value();
}

}  // namespace lancer
