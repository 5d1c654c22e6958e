#include "golden/octree.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "common/error.h"
#include "golden/isect.h"
#include "golden/memory_image.h"
#include "golden/wide.h"

namespace lancer::fx {

namespace {

constexpr OctT kMinusInf{0, -1}, kPlusInf{0, 1};

struct Box {
  std::array<int64_t, 3> lo{};
  int64_t side = kLatticeSide;
  Box child(int i) const {  // i = 4x + 2y + z: the upper half on each set axis
    const int64_t half = side / 2;
    return Box{{lo[0] + ((i >> 2) & 1) * half, lo[1] + ((i >> 1) & 1) * half, lo[2] + (i & 1) * half}, half};
  }
};

struct Builder {
  OctreeImage& image;
  PrimitiveTables primitives;
  void build(uint32_t index, const Box& box, int depth, const std::vector<uint32_t>& tris) {
    image.depth = std::max(image.depth, depth);
    if (depth < image.maxDepth && int(tris.size()) > image.leafSize) {
      std::array<std::vector<uint32_t>, 8> lists;
      size_t references = 0;
      for (int i = 0; i < 8; ++i) {
        const Box c = box.child(i);
        for (uint32_t entry : tris) {
          if (touches(primitives.bounds(entry), c)) lists[i].push_back(entry);
        }
        references += lists[i].size();
      }
      // Split only if it lowers the expected tests of a ray crossing the node:
      // each child's surface is a quarter of the parent's, so the children cost
      // sum(n_i) / 4 against the leaf's n. Around a shared vertex every child
      // keeps the whole fan and the split stops.
      if (references < 4 * tris.size()) {
        const uint32_t base = uint32_t(image.nodes.size());
        image.nodes.resize(image.nodes.size() + 8);
        image.nodes[index] = OctreeNode{false, base, 0};
        for (int i = 0; i < 8; ++i) build(base + uint32_t(i), box.child(i), depth + 1, lists[i]);
        return;
      }
    }
    image.nodes[index] = OctreeNode{true, uint32_t(image.indices.size()), uint32_t(tris.size())};
    image.indices.insert(image.indices.end(), tris.begin(), tris.end());
  }
  // The primitive's lattice box meets the closed box.
  static bool touches(const LatticeBox& tb, const Box& b) {
    for (int a = 0; a < 3; ++a) {
      if (tb.hi[a] < b.lo[a] || tb.lo[a] > b.lo[a] + b.side) return false;
    }
    return true;
  }
};

int exitAxis(const std::array<OctT, 3>& t) {
  if (t[0] < t[1]) {
    if (t[0] < t[2]) return 0;
  } else if (t[1] < t[2]) {
    return 1;
  }
  return 2;
}

OctT midpoint(const OctT& t0, const OctT& t1) {
  // Exact: t0 + t1 = (lo + hi - 2 o') * pair, and lo + hi is even for a node of side >= 2.
  return OctT{(t0.value + t1.value) / 2, 0};
}

bool negative(const OctT& t) { return t.inf < 0 || (t.inf == 0 && t.value < 0); }

struct Walker {
  const OctreeImage& image;
  const QRay& ray;
  const OctreeRaySetup& setup;
  OctreeTrace& trace;
  bool done = false;

  void visit(uint32_t index, const Box& box, const std::array<OctT, 3>& t0, const std::array<OctT, 3>& t1) {
    if (negative(t1[0]) || negative(t1[1]) || negative(t1[2])) return;  // behind the origin
    trace.visits.push_back(index);
    const OctreeNode& node = image.nodes[index];
    if (node.leaf) {
      for (uint32_t k = 0; k < node.count; ++k) testEntry(trace, ray, tablesOf(image), image.indices[node.first + k]);
      if (ray.anyHit && trace.hit) {  // any hit answers: no exit test
        done = true;
        return;
      }
      const auto bound = walkBound(ray, trace.hit);
      done = bound && hitWithin(*bound, t1, setup);
      return;
    }
    // Mid-plane parameters: halvings, or +-inf for an axis the ray never
    // crosses, by the side of the mid-plane the (mirrored) origin lies on.
    std::array<OctT, 3> tm{};
    for (int a = 0; a < 3; ++a) {
      tm[a] = setup.active[a] ? midpoint(t0[a], t1[a])
                              : (setup.origin[a] < box.lo[a] + box.side / 2 ? kPlusInf : kMinusInf);
    }
    for (int child = firstChild(t0, tm); child < 8 && !done;) {
      std::array<OctT, 3> c0{}, c1{};
      for (int a = 0; a < 3; ++a) {
        const bool upper = (child >> (2 - a)) & 1;
        c0[a] = upper ? tm[a] : t0[a];
        c1[a] = upper ? t1[a] : tm[a];
      }
      // The mirrored walk's child `child` is the stored child child ^ a.
      visit(node.first + uint32_t(child ^ setup.mirror), box.child(child), c0, c1);
      child = nextChild(child, c1);
    }
  }
};

}  // namespace

int defaultOctreeDepth(size_t triangles) {
  const double leaves = std::max(1.0, double(triangles) / kDefaultOctreeLeafSize);
  const int levels = int(std::ceil(std::log(leaves) / std::log(8.0))) + 3;
  return std::clamp(levels, 1, kOctreeMaxDepth);
}

OctreeImage buildOctreeImage(std::vector<QTriangle> triangles, int maxDepth, int leafSize,
                             std::vector<QQuadric> quadrics) {
  if (maxDepth < 1 || maxDepth > kOctreeMaxDepth) {
    throw InputError(fmt::format("octree depth {} is out of range: the {}-bit position format supports depths 1..{} "
                                 "(a node at depth {} is one lattice unit wide)",
                                 maxDepth, kPosBits, kOctreeMaxDepth, kOctreeMaxDepth));
  }
  if (leafSize < 1) throw InputError(fmt::format("octree leaf size {} must be at least 1", leafSize));
  OctreeImage image;
  image.maxDepth = maxDepth;
  image.leafSize = leafSize;
  image.triangles = std::move(triangles);
  image.quadrics = std::move(quadrics);
  const PrimitiveTables primitives = tablesOf(image);
  image.nodes.resize(1);
  Builder{image, primitives}.build(0, Box{}, 0, primitives.entries());
  checkRegionFits("octree", "node table", image.nodes.size(), "lower --octree-depth or raise --octree-leaf");
  checkRegionFits("octree", "index list", image.indices.size(), "lower --octree-depth or raise --octree-leaf");
  checkRegionFits("octree", "triangle table", image.triangles.size(), "use a smaller scene");
  checkRegionFits("octree", "quadric table", image.quadrics.size(), "use a smaller scene");
  return image;
}

OctreeRaySetup OctreeRaySetup::setup(const QRay& ray) {
  OctreeRaySetup s{MirroredRay::of(ray)};
  for (int a = 0; a < 3; ++a) {
    if (!s.active[a]) {
      // Quantized origins lie in the lattice, so inside the slab: the ray is in
      // it for all t.
      s.t0[a] = kMinusInf;
      s.t1[a] = kPlusInf;
      continue;
    }
    s.t0[a] = OctT{i128(0 - s.origin[a]) * s.pair[a], 0};
    s.t1[a] = OctT{i128(kLatticeSide - s.origin[a]) * s.pair[a], 0};
  }
  return s;
}

int firstChild(const std::array<OctT, 3>& t0, const std::array<OctT, 3>& tm) {
  int child = 0;
  if (t0[1] < t0[0]) {
    if (t0[2] < t0[0]) {  // entry plane YZ
      if (tm[1] < t0[0]) child |= 2;
      if (tm[2] < t0[0]) child |= 1;
      return child;
    }
  } else if (t0[2] < t0[1]) {  // entry plane XZ
    if (tm[0] < t0[1]) child |= 4;
    if (tm[2] < t0[1]) child |= 1;
    return child;
  }
  // entry plane XY
  if (tm[0] < t0[2]) child |= 4;
  if (tm[1] < t0[2]) child |= 2;
  return child;
}

int nextChild(int child, const std::array<OctT, 3>& childT1) {
  const int bit = 4 >> exitAxis(childT1);
  return (child & bit) ? 8 : (child | bit);
}

bool hitWithin(const IsectResult& hit, const std::array<OctT, 3>& t1, const OctreeRaySetup& ray) {
  const OctT exit = std::min({t1[0], t1[1], t1[2]});
  if (exit.inf > 0) return true;
  // t_hit = t_num / (|d[kz]| det) <= exit / common, all terms non-negative here.
  return !(mul256(u128(exit.value) * ray.dominant, hit.det) < mul256(hit.tNum, ray.common));
}

OctreeTrace traverseOctree(const OctreeImage& image, const QRay& ray) {
  OctreeTrace trace;
  const OctreeRaySetup setup = OctreeRaySetup::setup(ray);
  // Revelles' root test: the ray meets the root's interior.
  const OctT enter = std::max({setup.t0[0], setup.t0[1], setup.t0[2]});
  const OctT leave = std::min({setup.t1[0], setup.t1[1], setup.t1[2]});
  if (!(enter < leave)) return trace;
  Walker{image, ray, setup, trace}.visit(0, Box{}, setup.t0, setup.t1);
  return trace;
}

}  // namespace lancer::fx
