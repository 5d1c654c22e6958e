#include "golden/bvh.h"

#include <algorithm>
#include <bit>
#include <stdexcept>

#include <fmt/format.h>

#include "common/error.h"
#include "common/sah.h"
#include "golden/isect.h"
#include "golden/memory_image.h"
#include "golden/record_bits.h"
#include "golden/treelet_layout.h"
#include "golden/wide.h"

namespace lancer::fx {

namespace {

// Lattice coordinates are below 2^24, so exact floats: the SAH builder's boxes
// of the triangles' lattice boxes, and their unions, are lattice boxes too.
static_assert(kPosBits <= 24, "the SAH builder's float boxes must hold lattice coordinates exactly");

Aabb toAabb(const LatticeBox& b) {
  return Aabb{glm::vec3(float(b.lo[0]), float(b.lo[1]), float(b.lo[2])),
              glm::vec3(float(b.hi[0]), float(b.hi[1]), float(b.hi[2]))};
}

LatticeBox toLattice(const Aabb& b) {
  LatticeBox l;
  for (int a = 0; a < 3; ++a) {
    l.lo[a] = int64_t(b.lo[a]);
    l.hi[a] = int64_t(b.hi[a]);
  }
  return l;
}

// Turns the SAH tree into the image: interior nodes numbered in depth-first
// order, each holding its children's boxes quantized in its own frame.
struct Converter {
  const SahTree& tree;
  BvhImage& image;

  BvhRef convert(uint32_t index) {
    const SahNode& node = tree.nodes[index];
    if (node.leaf) return BvhRef{true, node.count(), node.begin};
    const uint32_t slot = uint32_t(image.nodes.size());
    image.nodes.emplace_back();
    BvhNode out;
    const LatticeBox box = toLattice(node.box);
    for (int a = 0; a < 3; ++a) {
      out.base[a] = box.lo[a];
      out.shift[a] = bvhShiftFor(box.hi[a] - box.lo[a]);
    }
    const std::array<uint32_t, kBvhWidth> children{index + 1, node.right};
    for (int c = 0; c < kBvhWidth; ++c) {
      const LatticeBox cb = toLattice(tree.nodes[children[c]].box);
      for (int a = 0; a < 3; ++a) {
        out.lo[c][a] = bvhPlaneDown(cb.lo[a], out.base[a], out.shift[a]);
        out.hi[c][a] = bvhPlaneUp(cb.hi[a], out.base[a], out.shift[a]);
      }
      out.child[c] = convert(children[c]);
    }
    image.nodes[slot] = out;
    return BvhRef{false, 0, slot};
  }
};

struct Walker {
  const BvhImage& image;
  const QRay& ray;
  const BvhRaySetup& setup;
  BvhWalk& walk;
  TreeletCrossings* crossings = nullptr;  // counted where the layout has treelet blocks
  uint32_t block = 0;                      // the block the walk is in (the root's at the start)
  bool suspends = false;                   // stop where it would cross into another block

  using Entry = BvhWalkEntry;

  void run() {
    TraversalTrace& trace = walk.trace;
    while (walk.next) {
      const Entry current = *walk.next;
      std::optional<Entry> next;
      const auto bound = walkBound(ray, trace.hit);
      if (!(bound && culledBy(*bound, current.entry, setup))) {
        if (image.treeletNodes != 0 && !current.ref.leaf && image.blockOf(current.ref.first) != block) {
          const bool suspension = walk.stack.size() <= size_t(kBvhSuspendEntries);
          if (suspends && suspension) return;  // walk.next waits for its block
          block = image.blockOf(current.ref.first);
          if (crossings) {
            ++crossings->crossings;
            if (suspension) {
              ++crossings->suspensions;
              crossings->stateBits += uint64_t(bvhSuspendedBits(walk.stack.size()));
            }
          }
        }
        trace.visits.push_back(current.ref.visitId());
        if (current.ref.leaf) {
          if (testLeaf(current.ref)) {
            walk.next.reset();
            return;
          }
        } else {
          next = descend(image.nodes[current.ref.first], walk.stack);
        }
      }
      if (!next && !walk.stack.empty()) {
        next = walk.stack.back();
        walk.stack.pop_back();
      }
      walk.next = next;
    }
  }

  // Tests every primitive of the leaf; true if an any-hit ray is answered.
  bool testLeaf(const BvhRef& leaf) {
    for (uint32_t k = 0; k < leaf.count; ++k) testEntry(walk.trace, ray, tablesOf(image), image.indices[leaf.first + k]);
    return ray.anyHit && walk.trace.hit.has_value();
  }

  // Both children's box tests; the nearer one entered next (child 0 on a
  // tie), the farther pushed.
  std::optional<Entry> descend(const BvhNode& node, std::vector<Entry>& stack) {
    std::array<BoxHit, kBvhWidth> hits;
    for (int c = 0; c < kBvhWidth; ++c) hits[c] = boxTest(setup, node.childLo(c), node.childHi(c));
    if (hits[0].hit && hits[1].hit) {
      const int near = hits[1].entry < hits[0].entry ? 1 : 0;
      if (stack.size() == size_t(kBvhStackDepth)) throw std::logic_error("BVH walk: the stack overflows");
      stack.push_back(Entry{node.child[1 - near], hits[1 - near].entry});
      return Entry{node.child[near], hits[near].entry};
    }
    for (int c = 0; c < kBvhWidth; ++c) {
      if (hits[c].hit) return Entry{node.child[c], hits[c].entry};
    }
    return std::nullopt;
  }
};

}  // namespace

std::array<int64_t, 3> BvhNode::childLo(int c) const {
  std::array<int64_t, 3> p{};
  for (int a = 0; a < 3; ++a) p[a] = bvhPlane(base[a], lo[c][a], shift[a]);
  return p;
}

std::array<int64_t, 3> BvhNode::childHi(int c) const {
  std::array<int64_t, 3> p{};
  for (int a = 0; a < 3; ++a) p[a] = bvhPlane(base[a], hi[c][a], shift[a]);
  return p;
}

int bvhShiftFor(int64_t extent) {
  int shift = 0;
  while ((int64_t(kBvhPlaneMax) << shift) < extent) ++shift;
  return shift;
}

uint32_t bvhPlaneDown(int64_t plane, int64_t base, int shift) { return uint32_t((plane - base) >> shift); }

uint32_t bvhPlaneUp(int64_t plane, int64_t base, int shift) {
  return uint32_t((plane - base + (int64_t(1) << shift) - 1) >> shift);
}

BvhImage buildBvhImage(std::vector<QTriangle> triangles, int leafSize, std::vector<QQuadric> quadrics) {
  if (leafSize < 1 || leafSize > kBvhMaxLeafSize) {
    throw InputError(fmt::format("BVH leaf size {} is out of range: the unit's {}-bit count allows 1..{}", leafSize,
                                 kBvhCountBits, kBvhMaxLeafSize));
  }
  BvhImage image;
  image.leafSize = leafSize;
  image.triangles = std::move(triangles);
  image.quadrics = std::move(quadrics);
  const PrimitiveTables primitives = tablesOf(image);
  const std::vector<uint32_t> entries = primitives.entries();
  std::vector<Aabb> boxes(entries.size());
  for (size_t i = 0; i < boxes.size(); ++i) boxes[i] = toAabb(primitives.bounds(entries[i]));
  const SahTree tree = buildSah(boxes, SahOptions{.leafSize = leafSize, .maxDepth = kBvhMaxLevels});
  image.indices.resize(tree.order.size());
  for (size_t i = 0; i < tree.order.size(); ++i) image.indices[i] = entries[tree.order[i]];
  image.depth = tree.depth;
  image.leaves = tree.leaves;
  if (!tree.nodes.empty()) {
    image.root = Converter{tree, image}.convert(0);
  } else {
    image.depth = 1;  // the root: an empty leaf
  }
  checkBvhImageFits(image);
  return image;
}

namespace {

// The surface area of child c's box as its parent frames it: the share of
// rays that enter it, up to a constant (the greedy treelets' priority).
double childArea(const BvhNode& node, int c) {
  const std::array<int64_t, 3> lo = node.childLo(c), hi = node.childHi(c);
  const double x = double(hi[0] - lo[0]), y = double(hi[1] - lo[1]), z = double(hi[2] - lo[2]);
  return x * y + y * z + z * x;
}

}  // namespace

void layoutBvhTreelets(BvhImage& image, uint32_t blockNodes) {
  if (!std::has_single_bit(blockNodes)) {
    throw InputError(fmt::format("BVH treelet blocks of {} nodes: a block must be a power of two", blockNodes));
  }
  // Primitives in leaf order (each is listed once), each kind in its table.
  renumberPrimitivesByListing(image.indices, image.triangles, image.quadrics);
  // Treelets of interior nodes, the largest child boxes first, packed next-fit into the blocks.
  std::vector<std::vector<uint32_t>> treelets;
  if (!image.nodes.empty()) {
    treelets = formGreedyTreelets(0, blockNodes, [&](uint32_t index, auto emit) {
      for (int c = 0; c < kBvhWidth; ++c) {
        const BvhRef& ref = image.nodes[index].child[size_t(c)];
        if (!ref.leaf) emit(childArea(image.nodes[index], c), ref.first);
      }
    });
  }
  std::vector<uint32_t> placed(image.nodes.size());
  const uint64_t slots =
      packTreeletsNextFit(treelets, blockNodes, 0, [&](uint32_t index, uint64_t slot) { placed[index] = uint32_t(slot); });
  std::vector<BvhNode> nodes(static_cast<size_t>(slots));
  for (size_t i = 0; i < image.nodes.size(); ++i) {
    BvhNode node = image.nodes[i];
    for (BvhRef& child : node.child) {
      if (!child.leaf) child.first = placed[child.first];
    }
    nodes[placed[i]] = node;
  }
  image.paddingNodes = nodes.size() - image.nodes.size();
  image.nodes = std::move(nodes);
  image.treeletNodes = blockNodes;
  image.treelets = treelets.size();
  checkBvhImageFits(image);
}

void checkBvhImageFits(const BvhImage& image, int addrBits) {
  // The index list and the primitive tables hold an entry a primitive, the
  // node table fewer: no leaf size helps, only a smaller scene.
  checkRegionFits("bvh", "node table", image.nodes.size(), "use a smaller scene", addrBits);
  checkRegionFits("bvh", "index list", image.indices.size(), "use a smaller scene", addrBits);
  checkRegionFits("bvh", "triangle table", image.triangles.size(), "use a smaller scene", addrBits);
  checkRegionFits("bvh", "quadric table", image.quadrics.size(), "use a smaller scene", addrBits);
}

bool culledBy(const IsectResult& bound, u128 entry, const BvhRaySetup& ray) {
  if (entry == 0) return false;
  // t_bound = t_num / (dominant det) <= (entry - 1) / common, all terms non-negative.
  return !(mul256((entry - 1) * ray.dominant, bound.det) < mul256(bound.tNum, ray.common));
}

BvhWalk startBvhWalk(const BvhImage& image) {
  BvhWalk walk;
  walk.next = BvhWalkEntry{image.root, 0};
  walk.stack.reserve(kBvhStackDepth);
  return walk;
}

void continueBvhWalk(const BvhImage& image, const QRay& ray, BvhWalk& walk, uint32_t block) {
  const BvhRaySetup setup = BvhRaySetup::setup(ray);
  Walker{image, ray, setup, walk, nullptr, block, true}.run();
}

namespace {

u128 refValue(const BvhRef& r) { return wire_bits::packValue<kBvhRefFields>({r.leaf ? 1u : 0u, r.count, r.first}); }
BvhRef refOf(u128 value) {
  const auto v = wire_bits::unpackValue<kBvhRefFields>(value);
  return BvhRef{v[0] != 0, uint32_t(v[1]), uint32_t(v[2])};
}

}  // namespace

std::array<u128, valueCount(kBvhWalkFields)> bvhWalkValues(const BvhWalk& walk) {
  if (walk.stack.size() > size_t(kBvhSuspendEntries) || !walk.next) {
    throw std::logic_error("bvh_walk_t: a finished walk, or a stack deeper than the suspend window");
  }
  std::array<u128, valueCount(kBvhWalkFields)> v{};
  putWalkHit(walk.trace.hit, v);
  size_t k = size_t(kWalkHitFields);
  for (const u128 x : {refValue(walk.next->ref), walk.next->entry, u128(walk.stack.size())}) v[k++] = x;
  for (size_t e = 0; e < walk.stack.size(); ++e) {
    v[k + e] = refValue(walk.stack[e].ref);
    v[k + size_t(kBvhSuspendEntries) + e] = walk.stack[e].entry;
  }
  return v;
}

BvhWalk bvhWalkOf(std::span<const u128> v, uint32_t rayId) {
  BvhWalk walk;
  walk.trace.hit = walkHitOf(v, rayId);
  constexpr size_t k = size_t(kWalkHitFields);
  walk.next = BvhWalkEntry{refOf(v[k]), v[k + 1]};
  const size_t sp = size_t(v[k + 2]);
  if (sp > size_t(kBvhSuspendEntries)) throw std::logic_error("bvh_walk_t: sp beyond the suspend window");
  walk.stack.reserve(kBvhStackDepth);
  for (size_t e = 0; e < sp; ++e) {
    walk.stack.push_back(BvhWalkEntry{refOf(v[k + 3 + e]), v[k + 3 + size_t(kBvhSuspendEntries) + e]});
  }
  return walk;
}

TraversalTrace traverseBvh(const BvhImage& image, const QRay& ray) {
  BvhWalk walk = startBvhWalk(image);
  const BvhRaySetup setup = BvhRaySetup::setup(ray);
  Walker{image, ray, setup, walk}.run();
  return std::move(walk.trace);
}

TreeletCrossings bvhTreeletCrossings(const BvhImage& image, const QRay& ray) {
  TreeletCrossings crossings;
  if (image.treeletNodes == 0) return crossings;
  BvhWalk walk = startBvhWalk(image);
  const BvhRaySetup setup = BvhRaySetup::setup(ray);
  Walker{image, ray, setup, walk, &crossings}.run();
  crossings.rays = 1;
  return crossings;
}

}  // namespace lancer::fx
