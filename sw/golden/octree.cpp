#include "golden/octree.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "common/error.h"
#include "golden/isect.h"
#include "golden/memory_image.h"
#include "golden/record_bits.h"
#include "golden/treelet_layout.h"
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

bool behind(const std::array<OctT, 3>& t1) { return negative(t1[0]) || negative(t1[1]) || negative(t1[2]); }

// rt_octree's walk, step for step (docs/octree-unit.md, "Slot state machine"):
// the node's plane parameters and the stack of {group base, child}, between
// its reads of child groups; a descent's read is where a treelet schedule may
// set it aside. It visits the nodes of Revelles' recursion in its order: the
// children a node's ray crosses, from firstChild by nextChild, a child behind
// the origin (some t1 < 0) skipped.
struct Stepper {
  const OctreeImage& image;
  const QRay& ray;
  const OctreeRaySetup& setup;
  OctreeWalk& walk;
  TreeletCrossings* crossings = nullptr;  // counted where the layout has treelet blocks
  uint32_t block = 0;                     // the block the walk is in
  bool suspends = false;                  // stop before a descent's read in another block
  bool groupHeld = false;                 // the stack top's group is in the unit (group_valid)

  void run() {
    if (walk.next == OctreeWalk::Next::Start) start();
    while (walk.next == OctreeWalk::Next::Descend || walk.next == OctreeWalk::Next::Refill) {
      if (image.treeletNodes != 0 && image.blockOf(walk.group) != block) {
        const bool suspension =
            walk.next == OctreeWalk::Next::Descend && walk.stack.size() <= size_t(kOctreeSuspendLevels);
        if (suspends && suspension) return;  // walk.group waits for its block
        block = image.blockOf(walk.group);
        if (crossings) {
          ++crossings->crossings;
          if (suspension) {
            ++crossings->suspensions;
            crossings->stateBits += uint64_t(octreeSuspendedBits(walk.stack.size()));
          }
        }
      }
      groupHeld = true;
      if (walk.next == OctreeWalk::Next::Descend) {
        descend();
      } else {
        const OctreeLevel& top = walk.stack.back();
        enter(top.first + uint32_t(top.child ^ setup.mirror));
      }
    }
  }

  // Revelles' root test, then the root (its record is the unit's configuration).
  void start() {
    const OctT in = std::max({setup.t0[0], setup.t0[1], setup.t0[2]});
    const OctT out = std::min({setup.t1[0], setup.t1[1], setup.t1[2]});
    walk.t0 = setup.t0;
    walk.t1 = setup.t1;
    if (!(in < out) || behind(walk.t1)) {
      walk.next = OctreeWalk::Next::Over;
      return;
    }
    enter(0);
  }

  // ENTER: the visit; an interior node waits for its group, a leaf is tested.
  void enter(uint32_t index) {
    walk.trace.visits.push_back(index);
    const OctreeNode& node = image.nodes[index];
    if (!node.leaf) {
      walk.next = OctreeWalk::Next::Descend;
      walk.group = node.first;
      return;
    }
    for (uint32_t k = 0; k < node.count; ++k) testEntry(walk.trace, ray, tablesOf(image), image.indices[node.first + k]);
    const auto bound = walkBound(ray, walk.trace.hit);
    if ((ray.anyHit && walk.trace.hit) || (bound && hitWithin(*bound, walk.t1, setup))) {
      walk.next = OctreeWalk::Next::Over;
      return;
    }
    advance();
  }

  // DESCEND into the first child; on an axis the ray never crosses, the side
  // of the mid-plane the origin lies on (the node's corner from the path).
  void descend() {
    const int depth = int(walk.stack.size());
    std::array<OctT, 3> tm{};
    for (int a = 0; a < 3; ++a) {
      if (setup.active[a]) {
        tm[a] = midpoint(walk.t0[a], walk.t1[a]);
        continue;
      }
      int64_t lo = 0;
      for (int k = 0; k < depth; ++k) lo += int64_t((walk.stack[size_t(k)].child >> (2 - a)) & 1) << (kPosBits - 1 - k);
      tm[a] = setup.origin[a] < lo + (int64_t(1) << (kPosBits - 1 - depth)) ? kPlusInf : kMinusInf;
    }
    const int child = firstChild(walk.t0, tm);
    walk.stack.push_back(OctreeLevel{walk.group, uint8_t(child)});
    for (int a = 0; a < 3; ++a) ((child >> (2 - a)) & 1 ? walk.t0 : walk.t1)[size_t(a)] = tm[a];
    if (behind(walk.t1)) {
      advance();
    } else {
      enter(walk.group + uint32_t(child ^ setup.mirror));
    }
  }

  // The advance: to the next sibling across the exit plane (Revelles' table
  // 2), or up a level (the parent's parameters from the child's).
  void advance() {
    while (!walk.stack.empty()) {
      OctreeLevel& top = walk.stack.back();
      const int x = exitAxis(walk.t1);
      const int bit = 4 >> x;
      if (!(top.child & bit)) {
        const OctT t0 = walk.t0[size_t(x)];
        walk.t0[size_t(x)] = walk.t1[size_t(x)];
        walk.t1[size_t(x)] = OctT{2 * walk.t1[size_t(x)].value - t0.value, 0};
        top.child = uint8_t(top.child | bit);
        if (behind(walk.t1)) continue;
        if (groupHeld) {
          enter(top.first + uint32_t(top.child ^ setup.mirror));
        } else {
          walk.next = OctreeWalk::Next::Refill;
          walk.group = top.first;
        }
        return;
      }
      for (int a = 0; a < 3; ++a) {
        if (!setup.active[a]) continue;
        OctT& t0 = walk.t0[size_t(a)];
        OctT& t1 = walk.t1[size_t(a)];
        if ((top.child >> (2 - a)) & 1) {
          t0.value = 2 * t0.value - t1.value;
        } else {
          t1.value = 2 * t1.value - t0.value;
        }
      }
      walk.stack.pop_back();
      groupHeld = false;
    }
    walk.next = OctreeWalk::Next::Over;
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
  OctreeWalk walk = startOctreeWalk(image);
  const OctreeRaySetup setup = OctreeRaySetup::setup(ray);
  Stepper{image, ray, setup, walk}.run();
  return std::move(walk.trace);
}

void layoutOctreeTreelets(OctreeImage& image, uint32_t blockNodes) {
  if (!std::has_single_bit(blockNodes) || blockNodes < uint32_t(kOctreeChildren)) {
    throw InputError(fmt::format("octree treelet blocks of {} nodes: a block is a power of two of at least one "
                                 "child group ({} nodes)",
                                 blockNodes, kOctreeChildren));
  }
  const uint32_t blockGroups = blockNodes / uint32_t(kOctreeChildren);
  // Treelets of child groups (each named by its first node), the shallowest
  // first (every node of a depth has the same surface), packed next-fit into
  // the blocks after the root's slot (entry 0 and seven entries of padding,
  // so that every group is aligned).
  std::vector<std::vector<uint32_t>> treelets;
  if (!image.nodes.empty() && !image.nodes[0].leaf) {
    std::vector<int> depthOf(image.nodes.size(), 0);
    depthOf[image.nodes[0].first] = 1;
    treelets = formGreedyTreelets(image.nodes[0].first, blockGroups, [&](uint32_t group, auto emit) {
      for (uint32_t n = group; n < group + uint32_t(kOctreeChildren); ++n) {
        if (image.nodes[n].leaf) continue;
        depthOf[image.nodes[n].first] = depthOf[group] + 1;
        emit(-double(depthOf[group] + 1), image.nodes[n].first);
      }
    });
  }
  std::vector<uint32_t> placed(image.nodes.size());
  const uint64_t slots = packTreeletsNextFit(treelets, blockGroups, 1, [&](uint32_t group, uint64_t slot) {
    placed[group] = uint32_t(slot * kOctreeChildren);
  });
  std::vector<OctreeNode> nodes(size_t(slots) * kOctreeChildren, OctreeNode{true, 0, 0});
  const auto relink = [&](OctreeNode node) {
    if (!node.leaf) node.first = placed[node.first];
    return node;
  };
  nodes[0] = relink(image.nodes[0]);
  for (const std::vector<uint32_t>& t : treelets) {
    for (uint32_t group : t) {
      for (uint32_t c = 0; c < uint32_t(kOctreeChildren); ++c) nodes[placed[group] + c] = relink(image.nodes[group + c]);
    }
  }
  // The index list in node-table order, then the primitives by first listing.
  std::vector<uint32_t> indices;
  indices.reserve(image.indices.size());
  for (OctreeNode& node : nodes) {
    if (!node.leaf || node.count == 0) continue;
    const auto run = std::span(image.indices).subspan(node.first, node.count);
    node.first = uint32_t(indices.size());
    indices.insert(indices.end(), run.begin(), run.end());
  }
  renumberPrimitivesByListing(indices, image.triangles, image.quadrics);
  for (const OctreeNode& node : nodes) {
    if (node.leaf && node.count > 1) std::sort(indices.begin() + node.first, indices.begin() + node.first + node.count);
  }
  image.paddingNodes = nodes.size() - image.nodes.size();
  image.nodes = std::move(nodes);
  image.indices = std::move(indices);
  image.treeletNodes = blockNodes;
  image.treelets = treelets.size();
  checkRegionFits("octree", "node table", image.nodes.size(), "lower --octree-depth or raise --octree-treelet-bytes");
}

OctreeWalk startOctreeWalk(const OctreeImage& image) {
  OctreeWalk walk;
  walk.group = image.nodes.empty() || image.nodes[0].leaf ? 0 : image.nodes[0].first;
  walk.stack.reserve(size_t(kOctreeStackDepth));
  return walk;
}

void continueOctreeWalk(const OctreeImage& image, const QRay& ray, OctreeWalk& walk, uint32_t block) {
  const OctreeRaySetup setup = OctreeRaySetup::setup(ray);
  Stepper{image, ray, setup, walk, nullptr, block, true}.run();
}

std::array<u128, valueCount(kOctreeWalkFields)> octreeWalkValues(const OctreeWalk& walk) {
  if (walk.stack.size() > size_t(kOctreeSuspendLevels) || walk.next != OctreeWalk::Next::Descend) {
    throw std::logic_error("octree_walk_t: a walk not about to descend, or a stack deeper than the suspend window");
  }
  std::array<u128, valueCount(kOctreeWalkFields)> v{};
  putWalkHit(walk.trace.hit, v);
  size_t k = size_t(kWalkHitFields);
  for (const u128 x : {u128(walk.group), u128(walk.stack.size())}) v[k++] = x;
  for (const auto* t : {&walk.t0, &walk.t1}) {
    for (const OctT& p : *t) v[k++] = p.inf == 0 ? u128(p.value) : 0;
  }
  for (size_t e = 0; e < walk.stack.size(); ++e) {
    v[k + e] = walk.stack[e].first;
    v[k + size_t(kOctreeSuspendLevels) + e] = walk.stack[e].child;
  }
  return v;
}

OctreeWalk octreeWalkOf(std::span<const u128> v, const QRay& ray) {
  const OctreeRaySetup setup = OctreeRaySetup::setup(ray);
  OctreeWalk walk;
  walk.trace.hit = walkHitOf(v, ray.id);
  size_t k = size_t(kWalkHitFields);
  walk.next = OctreeWalk::Next::Descend;
  walk.group = uint32_t(v[k]);
  const size_t depth = size_t(v[k + 1]);
  if (depth > size_t(kOctreeSuspendLevels)) throw std::logic_error("octree_walk_t: depth beyond the suspend window");
  k += 2;
  for (auto* t : {&walk.t0, &walk.t1}) {
    const OctT inactive = t == &walk.t0 ? kMinusInf : kPlusInf;
    for (int a = 0; a < 3; ++a, ++k) (*t)[size_t(a)] = setup.active[a] ? OctT{i128(v[k]), 0} : inactive;
  }
  walk.stack.reserve(size_t(kOctreeStackDepth));
  for (size_t e = 0; e < depth; ++e) {
    walk.stack.push_back(OctreeLevel{uint32_t(v[k + e]), uint8_t(v[k + size_t(kOctreeSuspendLevels) + e])});
  }
  return walk;
}

TreeletCrossings octreeTreeletCrossings(const OctreeImage& image, const QRay& ray) {
  TreeletCrossings crossings;
  if (image.treeletNodes == 0) return crossings;
  OctreeWalk walk = startOctreeWalk(image);
  const OctreeRaySetup setup = OctreeRaySetup::setup(ray);
  Stepper{image, ray, setup, walk, &crossings, walk.waitsFor(image)}.run();
  crossings.rays = 1;
  return crossings;
}

}  // namespace lancer::fx
