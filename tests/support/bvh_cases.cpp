#include "support/bvh_cases.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>

#include <fmt/format.h>

#include "driver/quantize.h"
#include "scene/scene.h"

namespace lancer::test {

namespace {

using fx::BvhImage;
using fx::kDirMax;
using fx::kPosMax;
using fx::QRay;
using fx::QTriangle;
using Vec = std::array<int64_t, 3>;

constexpr int64_t kSide = fx::kLatticeSide;

int64_t clampPos(int64_t v) { return std::clamp<int64_t>(v, 0, kPosMax); }
Vec clampVec(const Vec& v) { return {clampPos(v[0]), clampPos(v[1]), clampPos(v[2])}; }

// The child boxes of an image's interior nodes (lattice planes, clamped to the lattice).
std::vector<std::array<Vec, 2>> childBoxes(const BvhImage& image) {
  std::vector<std::array<Vec, 2>> boxes;
  for (const fx::BvhNode& n : image.nodes) {
    for (int c = 0; c < fx::kBvhWidth; ++c) boxes.push_back({clampVec(n.childLo(c)), clampVec(n.childHi(c))});
  }
  return boxes;
}

// Up to `count` of the image's child boxes, drawn at random (childBoxes shuffled).
std::vector<std::array<Vec, 2>> someChildBoxes(const BvhImage& image, std::mt19937_64& rng, size_t count) {
  std::vector<std::array<Vec, 2>> boxes = childBoxes(image);
  std::shuffle(boxes.begin(), boxes.end(), rng);
  boxes.resize(std::min(boxes.size(), count));
  return boxes;
}

BvhCase makeCase(std::string name, BvhImage image, std::vector<QRay> rays) {
  return makeTraversalCase("bvh", std::move(name), std::move(image), std::move(rays));
}

// ---- The cases ------------------------------------------------------------------

BvhCase axisParallel() {
  std::mt19937_64 rng(201);
  const BvhImage image = fx::buildBvhImage(quantizedCornell(), 2);
  std::vector<QRay> rays;
  for (const auto& [lo, hi] : someChildBoxes(image, rng, 12)) {
    for (int axis = 0; axis < 3; ++axis) {
      for (int64_t sign : {1, -1}) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        // On the box's planes, one unit inside and outside them, and through its middle.
        for (const auto& [pu, pv] : std::array<std::array<int64_t, 2>, 5>{
                 {{lo[u], lo[v]}, {hi[u], hi[v]}, {lo[u] + 1, hi[v] - 1}, {lo[u] - 1, hi[v] + 1},
                  {(lo[u] + hi[u]) / 2, (lo[v] + hi[v]) / 2}}}) {
          QRay r{0, {}, {0, 0, 0}};
          r.org[axis] = sign > 0 ? 0 : kPosMax;
          r.org[u] = clampPos(pu);
          r.org[v] = clampPos(pv);
          r.dir[axis] = sign * kDirMax;
          rays.push_back(r);
        }
      }
    }
  }
  return makeCase("axis_parallel", image, std::move(rays));
}

BvhCase boxCorners() {
  std::mt19937_64 rng(202);
  const BvhImage image = fx::buildBvhImage(quantizeScene(subdivide(makeCornellBox(), 1)), 2);
  std::vector<QRay> rays;
  for (const auto& [lo, hi] : someChildBoxes(image, rng, 10)) {
    // From each corner along the diagonals (through the opposite corner when the box is a cube) ...
    for (int corner = 0; corner < 8; ++corner) {
      const Vec at{(corner & 4) ? hi[0] : lo[0], (corner & 2) ? hi[1] : lo[1], (corner & 1) ? hi[2] : lo[2]};
      addOctantRays(rays, at, {kDirMax, kDirMax, kDirMax});
      // ... along its edges (two zero components) ...
      rays.push_back(QRay{0, at, {(corner & 4) ? -kDirMax : kDirMax, 0, 0}});
      rays.push_back(QRay{0, at, {0, (corner & 2) ? -kDirMax : kDirMax, 0}});
      // ... and aimed at the other corners.
      const int other = 7 - corner;
      const Vec to{(other & 4) ? hi[0] : lo[0], (other & 2) ? hi[1] : lo[1], (other & 1) ? hi[2] : lo[2]};
      rays.push_back(aimedRay(at, to));
      rays.push_back(aimedRay(clampVec({2 * at[0] - to[0], 2 * at[1] - to[1], 2 * at[2] - to[2]}), to));
    }
  }
  return makeCase("box_corners", image, std::move(rays));
}

BvhCase boxFaces() {
  std::mt19937_64 rng(203);
  const BvhImage image = fx::buildBvhImage(quantizedCornell(), 1);
  std::uniform_int_distribution<int64_t> dir(-kDirMax, kDirMax);
  std::vector<QRay> rays;
  for (const auto& [lo, hi] : someChildBoxes(image, rng, 16)) {
    for (int axis = 0; axis < 3; ++axis) {
      for (const int64_t plane : {lo[axis], hi[axis]}) {
        Vec at{};
        for (int a = 0; a < 3; ++a) at[a] = std::uniform_int_distribution<int64_t>(lo[a], hi[a])(rng);
        at[axis] = plane;
        // In the face (no component across it), leaving through it, entering through it.
        Vec in{dir(rng), dir(rng), dir(rng)};
        in[axis] = 0;
        if (in == Vec{0, 0, 0}) in[(axis + 1) % 3] = kDirMax;
        rays.push_back(normalizedDirection(QRay{0, at, in}));
        const int64_t out = plane == hi[axis] ? 1 : -1;
        Vec leave{dir(rng), dir(rng), dir(rng)}, enter = leave;
        leave[axis] = out * std::max<int64_t>(1, std::abs(leave[axis]));
        enter[axis] = -leave[axis];
        rays.push_back(normalizedDirection(QRay{0, at, leave}));
        rays.push_back(normalizedDirection(QRay{0, at, enter}));
        Vec straight{0, 0, 0};
        straight[axis] = out * kDirMax;
        rays.push_back(QRay{0, at, straight});
        straight[axis] = -straight[axis];
        rays.push_back(QRay{0, at, straight});
      }
    }
  }
  return makeCase("box_faces", image, std::move(rays));
}

BvhCase octants() {
  std::mt19937_64 rng(204);
  std::vector<QRay> rays;
  const int64_t m = kSide / 2;
  for (const Vec& org : {Vec{m, m, m}, Vec{0, 0, 0}, Vec{kPosMax, kPosMax, kPosMax}, Vec{m / 3, m + m / 2, m / 5},
                         randomLatticePoint(rng), randomLatticePoint(rng)}) {
    addOctantRays(rays, org, {kDirMax, kDirMax / 3, kDirMax / 7});
    addOctantRays(rays, org, {kDirMax / 5, kDirMax, 11});
    addOctantRays(rays, org, {kDirMax, kDirMax, kDirMax});
  }
  return makeCase("octants", fx::buildBvhImage(quantizedCornell(), 4), std::move(rays));
}

BvhCase crowdedLeaf() {
  // 255 copies of one triangle (one box: the SAH cannot split them) beside a
  // few others: a leaf of 255, and ties of the closest hit broken by id.
  std::vector<QTriangle> tris;
  const int64_t c = kSide / 2, s = kSide / 64;
  for (uint32_t i = 0; i < uint32_t(fx::kBvhMaxLeafSize); ++i) {
    tris.push_back(QTriangle{i, {{{c - s, c - s, c}, {c + s, c - s, c + s / 16}, {c, c + s, c - s / 16}}}});
  }
  for (uint32_t i = 0; i < 6; ++i) {
    const int64_t o = kSide / 16 + int64_t(i) * kSide / 8, e = kSide / 128;
    tris.push_back(QTriangle{uint32_t(tris.size()), {{{o, o, e}, {o + e, o, 2 * e}, {o, o + e, 3 * e}}}});
  }
  BvhImage image = fx::buildBvhImage(tris, fx::kBvhMaxLeafSize);
  bool full = image.root.leaf && image.root.count == uint32_t(fx::kBvhMaxLeafSize);
  for (const fx::BvhNode& n : image.nodes) {
    for (const fx::BvhRef& r : n.child) full = full || (r.leaf && r.count == uint32_t(fx::kBvhMaxLeafSize));
  }
  if (!full) throw std::logic_error("bvh case crowded_leaf: no leaf of 255 triangles");
  std::mt19937_64 rng(205);
  std::vector<QRay> rays;
  std::uniform_int_distribution<int64_t> near(c - s * 2 / 3, c + s * 2 / 3);
  for (int i = 0; i < 24; ++i) {
    rays.push_back(aimedRay({near(rng), near(rng), i % 2 ? 0 : kPosMax}, {near(rng), near(rng), c}));
  }
  for (int i = 0; i < 8; ++i) rays.push_back(randomLatticeRay(rng, 0));
  return makeCase("crowded_leaf", std::move(image), std::move(rays));
}

BvhCase rootLeaf() {
  // One triangle three times (one box: the SAH cannot split them): a root leaf of 3, ties by id.
  std::vector<QTriangle> tris(3, quantizedCornell()[5]);
  for (uint32_t i = 0; i < 3; ++i) tris[i].id = i;
  std::mt19937_64 rng(206);
  std::vector<QRay> rays;
  for (const QTriangle& t : tris) {
    for (int i = 0; i < 4; ++i) {
      const Vec to{(t.v[0][0] + t.v[1][0] + t.v[2][0]) / 3, (t.v[0][1] + t.v[1][1] + t.v[2][1]) / 3,
                   (t.v[0][2] + t.v[1][2] + t.v[2][2]) / 3};
      rays.push_back(aimedRay(randomLatticePoint(rng), to));
    }
  }
  for (int i = 0; i < 8; ++i) rays.push_back(randomLatticeRay(rng, 0));
  BvhImage image = fx::buildBvhImage(tris, 4);
  if (!image.root.leaf) throw std::logic_error("bvh case root_leaf: the root is not a leaf");
  return makeCase("root_leaf", std::move(image), std::move(rays));
}

BvhCase empty() {
  std::mt19937_64 rng(207);
  std::vector<QRay> rays;
  for (int i = 0; i < 6; ++i) rays.push_back(randomLatticeRay(rng, 0));
  return makeCase("empty", fx::buildBvhImage({}, 4), std::move(rays));
}

BvhCase chain() {
  std::vector<QRay> rays{QRay{0, {5, 5, 5}, {kDirMax, 3, 7}}, QRay{0, {kPosMax, 9, kPosMax}, {-kDirMax, 1, -kDirMax}},
                         QRay{0, {kSide / 2, kSide / 3, kSide / 4}, {0, 0, -kDirMax}}};
  return makeCase("chain", bvhChainImage(fx::kBvhMaxLevels), std::move(rays));
}

BvhCase tinyComponents() {
  std::mt19937_64 rng(208);
  std::vector<QRay> rays;
  for (int i = 0; i < 48; ++i) {
    QRay r{0, randomLatticePoint(rng), {kDirMax, 1, -1}};
    std::shuffle(r.dir.begin(), r.dir.end(), rng);
    if (i % 2) r.dir[size_t(i % 3)] = -r.dir[size_t(i % 3)];
    if (i % 5 == 0) r.dir[size_t((i + 1) % 3)] = r.dir[size_t((i + 1) % 3)] == 1 ? 0 : r.dir[size_t((i + 1) % 3)];
    rays.push_back(normalizedDirection(r));
  }
  return makeCase("tiny_components", fx::buildBvhImage(quantizedCornell(), 2), std::move(rays));
}

BvhCase cornellRandom() {
  std::mt19937_64 rng(209);
  std::vector<QRay> rays;
  addAimedRays(rays, quantizedCornell(), rng, 120);
  addRandomRays(rays, rng, 80);
  return makeCase("cornell_random", fx::buildBvhImage(quantizedCornell(), fx::kDefaultBvhLeafSize), std::move(rays));
}

BvhCase cornellSegments() {
  std::mt19937_64 rng(210);
  std::vector<QRay> base;
  addAimedRays(base, quantizedCornell(), rng, 30);
  return makeCase("cornell_segments", fx::buildBvhImage(quantizedCornell(), 2), segmentVariants(quantizedCornell(), base, base.size()));
}

}  // namespace

// A root whose two children are empty leaves spanning the lattice.
BvhImage bvhTwoEmptyLeaves() {
  BvhImage image;
  image.leafSize = 1;
  const int shift = fx::bvhShiftFor(int64_t(1) << fx::kPosBits);
  fx::BvhNode node;
  node.shift = {shift, shift, shift};
  for (int c = 0; c < fx::kBvhWidth; ++c) node.hi[size_t(c)] = {fx::kBvhPlaneMax, fx::kBvhPlaneMax, fx::kBvhPlaneMax};
  node.child[0] = fx::BvhRef{true, 0, 0};
  node.child[1] = fx::BvhRef{true, 0, 0};
  image.nodes.push_back(node);
  image.root = fx::BvhRef{false, 0, 0};
  image.depth = 2;
  image.leaves = 2;
  return image;
}

BvhImage bvhChainImage(int levels) {
  BvhImage image;
  image.leafSize = 1;
  image.triangles = quantizedCornell();
  image.indices = {0};
  const int shift = fx::bvhShiftFor(kSide);
  for (int k = 0; k + 1 < levels; ++k) {
    fx::BvhNode node;
    node.shift = {shift, shift, shift};
    for (int c = 0; c < fx::kBvhWidth; ++c) node.hi[size_t(c)] = {fx::kBvhPlaneMax, fx::kBvhPlaneMax, fx::kBvhPlaneMax};
    node.child[0] = k + 2 < levels ? fx::BvhRef{false, 0, uint32_t(k + 1)} : fx::BvhRef{true, 1, 0};
    node.child[1] = fx::BvhRef{true, 1, 0};
    image.nodes.push_back(node);
  }
  image.root = fx::BvhRef{false, 0, 0};
  image.depth = levels;
  image.leaves = size_t(levels);
  return image;
}

std::vector<BvhCase> bvhHardCases() {
  return makeCases<BvhCase>({axisParallel, boxCorners, boxFaces, octants, crowdedLeaf, rootLeaf, empty, chain,
                             tinyComponents, cornellRandom, cornellSegments});
}

}  // namespace lancer::test
