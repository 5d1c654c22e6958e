#include "support/octree_cases.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "driver/quantize.h"
#include "golden/isect.h"
#include "scene/camera.h"

namespace lancer::test {

namespace {

using fx::kDirMax;
using fx::kOctreeMaxDepth;
using fx::kPosBits;
using fx::kPosMax;
using fx::OctreeImage;
using fx::QRay;
using fx::QTriangle;
using Vec = std::array<int64_t, 3>;

constexpr int64_t kSide = int64_t(1) << kPosBits;  // the root cube [0, 2^P]^3
constexpr int64_t kMid = kSide / 2;                // the root's mid-planes

int64_t clampPos(int64_t v) { return std::clamp<int64_t>(v, 0, kPosMax); }
int depthAtMost(int depth) { return std::min(depth, kOctreeMaxDepth); }

Vec randomDir(std::mt19937_64& rng) {
  std::uniform_int_distribution<int64_t> dir(-kDirMax, kDirMax);
  return {dir(rng), dir(rng), dir(rng)};
}

QRay randomRay(std::mt19937_64& rng) { return randomLatticeRay(rng, 0); }

OctreeCase makeCase(std::string name, OctreeImage image, std::vector<QRay> rays) {
  return makeTraversalCase("octree", std::move(name), std::move(image), std::move(rays));
}

// `count` random rays from a generator seeded with `seed`, ray i moved by
// place(i, ray, generator) onto a node's plane, face or edge, then normalized.
template <class Place>
std::vector<QRay> placedRays(uint64_t seed, int count, Place place) {
  std::mt19937_64 rng(seed);
  std::vector<QRay> rays;
  for (int i = 0; i < count; ++i) {
    QRay r{0, randomLatticePoint(rng), randomDir(rng)};
    place(i, r, rng);
    rays.push_back(normalizedDirection(r));
  }
  return rays;
}

// ---- The cases ------------------------------------------------------------------

OctreeCase axisParallel() {
  std::mt19937_64 rng(101);
  std::uniform_int_distribution<int64_t> pos(0, kPosMax);
  // In the root's mid-planes, one unit off them, on the root's faces, in the
  // mid-planes of depth-1 and depth-2 nodes, and anywhere.
  const int64_t at[] = {kMid, kMid - 1, 0, kPosMax, kMid / 2, kMid + kMid / 2, 3 * kSide / 8, pos(rng)};
  std::vector<QRay> rays;
  for (int axis = 0; axis < 3; ++axis) {
    for (int64_t sign : {1, -1}) {
      for (size_t i = 0; i < std::size(at); ++i) {
        for (size_t j = 0; j < std::size(at); j += 2) {
          QRay r{0, {}, {0, 0, 0}};
          r.org[axis] = (i + j) % 3 == 0 ? (sign > 0 ? 0 : kPosMax) : pos(rng);
          r.org[(axis + 1) % 3] = at[i];
          r.org[(axis + 2) % 3] = at[(i + j + 1) % std::size(at)];
          r.dir[axis] = sign * kDirMax;
          rays.push_back(r);
        }
      }
    }
  }
  return makeCase("axis_parallel", fx::buildOctreeImage(quantizedCornell(), depthAtMost(6), 2), std::move(rays));
}

OctreeCase midPlanes() {
  std::uniform_int_distribution<int> level(1, std::min(8, kPosBits)), odd(0, 127);
  std::vector<QRay> rays = placedRays(102, 240, [&](int i, QRay& r, std::mt19937_64& rng) {
    const int axis = i % 3;
    // The mid-plane of a node at depth k - 1: an odd multiple of 2^(P-k).
    const int k = (i % 4 == 0) ? 1 : level(rng);
    const int64_t step = kSide >> k;
    r.org[axis] = clampPos((2 * (odd(rng) % (int64_t(1) << (k - 1))) + 1) * step);
    r.dir[axis] = 0;
    if (i % 5 == 0) r.dir[(axis + 1) % 3] = 0;  // along a line in the plane
    if (r.dir == Vec{0, 0, 0}) r.dir[(axis + 2) % 3] = kDirMax;
  });
  return makeCase("mid_planes", fx::buildOctreeImage(quantizeScene(subdivide(makeCornellBox(), 1)), depthAtMost(7), 2),
                  std::move(rays));
}

OctreeCase centreAndCorners() {
  std::mt19937_64 rng(103);
  std::vector<QRay> rays;
  // Through the centre of the root along every diagonal (exact ties on all axes).
  addOctantRays(rays, {kMid, kMid, kMid}, {kDirMax, kDirMax, kDirMax});
  addOctantRays(rays, {kMid, kMid, kMid}, {kDirMax, kDirMax, 0});
  addOctantRays(rays, {kMid, 0, kMid}, {kDirMax, 0, kDirMax});
  addOctantRays(rays, {kMid - 1, kMid - 1, kMid - 1}, {kDirMax, kDirMax, kDirMax});
  std::uniform_int_distribution<int> level(1, std::min(8, kPosBits)), cell(0, 255), sign(0, 1);
  for (int i = 0; i < 300; ++i) {
    // A node corner at some depth; a direction through the next corners
    // (diagonal: ties on every axis), along a face diagonal, or along an edge.
    const int64_t step = kSide >> level(rng);
    Vec corner{};
    for (auto& c : corner) c = clampPos(int64_t(cell(rng)) % (kSide / step + 1) * step);
    Vec dir{kDirMax, kDirMax, kDirMax};
    if (i % 3 == 1) dir[(i / 3) % 3] = 0;  // a face diagonal
    if (i % 3 == 2) {                        // a node edge
      dir = {0, 0, 0};
      dir[(i / 3) % 3] = kDirMax;
    }
    for (auto& d : dir) d = sign(rng) ? -d : d;
    rays.push_back(normalizedDirection(QRay{0, corner, dir}));
  }
  return makeCase("centre_and_corners",
                  fx::buildOctreeImage(quantizeScene(subdivide(makeCornellBox(), 2)), depthAtMost(8), 4),
                  std::move(rays));
}

OctreeCase octants() {
  std::mt19937_64 rng(104);
  std::vector<QRay> rays;
  const Vec origins[] = {{kMid, kMid, kMid}, {kMid - 77, kMid + 31, kMid + 5}, {1, 2, 3},
                         {kPosMax, kPosMax - 3, kPosMax}, randomLatticePoint(rng), randomLatticePoint(rng)};
  for (const Vec& org : origins) {
    addOctantRays(rays, org, {kDirMax, kDirMax / 3, kDirMax / 5});
    addOctantRays(rays, org, {kDirMax / 7, kDirMax, kDirMax / 2});
    addOctantRays(rays, org, {kDirMax / 4, kDirMax / 9, kDirMax});
  }
  return makeCase("octants", fx::buildOctreeImage(quantizedCornell(), depthAtMost(6), 2), std::move(rays));
}

OctreeCase nodeFaces() {
  std::uniform_int_distribution<int> level(1, std::min(9, kPosBits)), cell(0, 511);
  std::vector<QRay> rays = placedRays(105, 300, [&](int i, QRay& r, std::mt19937_64& rng) {
    const int64_t step = kSide >> level(rng);
    const int axis = i % 3;
    r.org[axis] = clampPos(int64_t(cell(rng)) % (kSide / step + 1) * step);  // on a face of a node
    if (i % 4 == 1) r.org[(axis + 1) % 3] = clampPos(int64_t(cell(rng)) % (kSide / step + 1) * step);  // an edge
    if (i % 6 == 2) r.dir[axis] = 0;  // lying in the face
    if (i % 6 == 3) r.dir[axis] = (r.dir[axis] < 0 ? -1 : 1) * kDirMax;  // leaving along its normal
    if (r.dir == Vec{0, 0, 0}) r.dir[0] = kDirMax;
  });
  return makeCase("node_faces", fx::buildOctreeImage(quantizeScene(subdivide(makeCornellBox(), 2)), depthAtMost(8), 2),
                  std::move(rays));
}

OctreeCase rootFaces() {
  std::mt19937_64 rng(106);
  std::uniform_int_distribution<int> bit(0, 1);
  std::vector<QRay> rays;
  for (int i = 0; i < 200; ++i) {
    QRay r{0, randomLatticePoint(rng), randomDir(rng)};
    // On one, two (an edge) or three (a corner) faces of the root.
    for (int a = 0; a < 1 + i % 3; ++a) r.org[(i + a) % 3] = bit(rng) ? kPosMax : 0;
    if (i % 7 == 0) r.dir[i % 3] = 0;
    if (r.dir == Vec{0, 0, 0}) r.dir[1] = kDirMax;
    rays.push_back(normalizedDirection(r));
  }
  // At 0 on an axis, going down, the mirrored origin is 2^P: the ray leaves
  // through that face at t = 0. With another axis at 0 going up (it enters
  // there at t = 0) the ray only touches the root and misses it.
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      if (a == b) continue;
      QRay r{0, randomLatticePoint(rng), {kDirMax / 2, kDirMax / 3, kDirMax / 5}};
      r.org[a] = 0;
      r.dir[a] = -kDirMax;
      rays.push_back(normalizedDirection(r));  // leaves at t = 0 on a, inside on the others
      r.org[b] = 0;
      rays.push_back(normalizedDirection(r));  // misses the root
      r.dir[b] = -r.dir[b];
      rays.push_back(normalizedDirection(r));  // leaves on two faces at t = 0
    }
  }
  rays.push_back(QRay{0, {0, 0, 0}, {-kDirMax, -kDirMax, -kDirMax}});
  rays.push_back(QRay{0, {0, 0, 0}, {kDirMax, kDirMax, kDirMax}});
  rays.push_back(QRay{0, {kPosMax, kPosMax, kPosMax}, {kDirMax, kDirMax, kDirMax}});
  rays.push_back(QRay{0, {kPosMax, kPosMax, kPosMax}, {-kDirMax, -kDirMax, -kDirMax}});
  return makeCase("root_faces", fx::buildOctreeImage(quantizedCornell(), depthAtMost(6), 2), std::move(rays));
}

// A cluster of tiny triangles forces leaves one lattice unit wide.
std::vector<QTriangle> tinyCluster() {
  std::vector<QTriangle> tris;
  const int64_t base = kSide / 3;
  for (uint32_t i = 0; i < 40; ++i) {
    const int64_t x = base + i % 5, y = base + i / 5 % 4, z = base + i / 20;
    tris.push_back(QTriangle{i, {{{x, y, z}, {x + 1, y, z}, {x, y + 1, z + 1}}}});
  }
  return tris;
}

OctreeCase deepLeafOrigins() {
  std::mt19937_64 rng(107);
  const int64_t base = kSide / 3;
  std::uniform_int_distribution<int64_t> near(base - 3, base + 8), in(0, 2);
  std::vector<QRay> rays;
  for (int i = 0; i < 200; ++i) {
    QRay r = randomRay(rng);
    r.org = {near(rng), near(rng), near(rng)};
    if (i % 4 == 0) r.org = {base + in(rng), base + in(rng), base + in(rng)};
    rays.push_back(r);
  }
  return makeCase("deep_leaf_origins", fx::buildOctreeImage(tinyCluster(), kOctreeMaxDepth, 1), std::move(rays));
}

OctreeCase maxDepth() {
  std::mt19937_64 rng(108);
  const std::vector<QTriangle> tris = tinyCluster();
  std::vector<QRay> rays;
  addAimedRays(rays, tris, rng, 150);  // from anywhere down to the unit-wide leaves
  addRandomRays(rays, rng, 50);
  OctreeImage image = fx::buildOctreeImage(tris, kOctreeMaxDepth, 1);
  if (image.depth < kOctreeMaxDepth - 1) {
    throw std::logic_error(fmt::format("octree case max_depth reaches depth {} only", image.depth));
  }
  return makeCase("max_depth", std::move(image), std::move(rays));
}

// The Cornell box squeezed into one corner of the lattice (a quarter of it).
std::vector<QTriangle> cornellInCorner(bool high) {
  std::vector<QTriangle> tris = quantizedCornell();
  for (QTriangle& t : tris) {
    for (auto& v : t.v)
      for (auto& c : v) c = high ? clampPos(kSide - kSide / 4 + c / 4) : c / 4;
  }
  return tris;
}

OctreeCase offCentre(bool high) {
  std::mt19937_64 rng(high ? 110 : 109);
  const std::vector<QTriangle> tris = cornellInCorner(high);
  std::vector<QRay> rays;
  std::uniform_int_distribution<size_t> pick(0, tris.size() - 1);
  std::uniform_int_distribution<int64_t> far(kSide / 4, kPosMax), close(0, 3 * kSide / 4);
  for (int i = 0; i < 200; ++i) {
    // The low scene seen from above it: every axis mirrored. The high scene
    // from below and from above.
    const Vec org = high ? (i % 2 ? Vec{close(rng), close(rng), close(rng)} : randomLatticePoint(rng))
                         : Vec{far(rng), far(rng), far(rng)};
    QRay r = aimedRay(org, centroid(tris[pick(rng)]));
    if (!high && i % 3 == 0) {
      r = randomRay(rng);
      r.org = org;
      for (auto& d : r.dir) d = -std::abs(d);
      r = normalizedDirection(r);
    }
    rays.push_back(r);
  }
  return makeCase(high ? "off_centre_high" : "off_centre_low", fx::buildOctreeImage(tris, depthAtMost(7), 2),
                  std::move(rays));
}

OctreeCase deepSparse() {
  std::mt19937_64 rng(111);
  // Three small triangles close together in a corner: the build splits around
  // them down to the depth limit, and a ray crossing the root passes empty
  // siblings at every level.
  const std::vector<QTriangle> tris{QTriangle{0, {{{1, 1, 1}, {6, 1, 1}, {1, 6, 3}}}},
                                    QTriangle{1, {{{3, 2, 2}, {4, 7, 2}, {2, 4, 6}}}},
                                    QTriangle{2, {{{2, 5, 4}, {7, 6, 1}, {3, 1, 3}}}}};
  std::vector<QRay> rays{QRay{0, {kPosMax, kPosMax, 3}, {-kDirMax, -kDirMax, 0}}};
  for (int i = 0; i < 100; ++i) rays.push_back(aimedRay(randomLatticePoint(rng), {2 + i % 5, 2 + i % 4, 1 + i % 3}));
  addRandomRays(rays, rng, 40);
  // Inside [0, 8]^3 the triangles separate no sooner than at depth P - 3.
  OctreeImage image = fx::buildOctreeImage(tris, depthAtMost(10), 1);
  if (image.depth < std::min(depthAtMost(10), kPosBits - 4)) {
    throw std::logic_error(fmt::format("octree case deep_sparse reaches depth {} only", image.depth));
  }
  return makeCase("deep_sparse", std::move(image), std::move(rays));
}

OctreeCase full() {
  std::mt19937_64 rng(112);
  const std::vector<QTriangle> tris = quantizeScene(subdivide(makeCornellBox(), 3));
  return makeCase("full", fx::buildOctreeImage(tris, depthAtMost(9), 1), randomAndAimedRays(rng, tris, 150, 50));
}

OctreeCase emptyLeaves() {
  std::mt19937_64 rng(113);
  // Six pairs of small triangles, each pair close together: the build splits
  // around each pair for several levels, leaving empty siblings behind.
  std::vector<QTriangle> tris;
  const std::vector<QTriangle> centres = randomLatticeTriangles(rng, 6, kSide / 16, kSide - kSide / 16, 0);
  std::uniform_int_distribution<int64_t> off(-kSide / 512, kSide / 512);
  for (const QTriangle& c : centres) {
    for (int k = 0; k < 2; ++k) {
      QTriangle t;
      t.id = uint32_t(tris.size());
      for (auto& v : t.v)
        for (int a = 0; a < 3; ++a) v[a] = clampPos(c.v[0][a] + (k ? kSide / 256 : 0) + off(rng));
      tris.push_back(t);
    }
  }
  OctreeImage image = fx::buildOctreeImage(tris, depthAtMost(8), 1);
  size_t emptyLeaves = 0;
  for (const fx::OctreeNode& n : image.nodes) emptyLeaves += n.leaf && n.count == 0;
  if (emptyLeaves * 2 < image.nodes.size()) {
    throw std::logic_error(fmt::format("octree case empty_leaves has {} empty leaves of {} nodes", emptyLeaves,
                                       image.nodes.size()));
  }
  return makeCase("empty_leaves", std::move(image), randomAndAimedRays(rng, tris, 150, 60));
}

OctreeCase crowdedLeaf() {
  std::mt19937_64 rng(114);
  // Large triangles over one region: splitting never pays, so leaves keep hundreds.
  const std::vector<QTriangle> tris = randomLatticeTriangles(rng, 300, kSide / 4 + kSide / 16, kMid - kSide / 16, kSide / 16);
  OctreeImage image = fx::buildOctreeImage(tris, depthAtMost(4), 8);
  uint32_t most = 0;
  for (const fx::OctreeNode& n : image.nodes) most = std::max(most, n.leaf ? n.count : 0u);
  if (most < 100) throw std::logic_error(fmt::format("octree case crowded_leaf: largest leaf holds {} only", most));
  std::uniform_int_distribution<int64_t> in(kSide / 4 + 2, kMid - 2);
  std::vector<QRay> rays;
  for (int i = 0; i < 30; ++i) {
    QRay r = randomRay(rng);
    if (i % 2 == 0) r.org = {in(rng), in(rng), in(rng)};  // starts in the crowd
    rays.push_back(r);
  }
  return makeCase("crowded_leaf", std::move(image), std::move(rays));
}

OctreeCase rootLeaf() {
  std::mt19937_64 rng(115);
  const std::vector<QTriangle> tris = randomLatticeTriangles(rng, 5, kSide / 8, kSide - kSide / 8, kSide / 8);
  return makeCase("root_leaf", fx::buildOctreeImage(tris, depthAtMost(4), 8), randomAndAimedRays(rng, tris, 40, 20));
}

OctreeCase empty() {
  std::mt19937_64 rng(116);
  std::vector<QRay> rays;
  addRandomRays(rays, rng, 30);
  return makeCase("empty", fx::buildOctreeImage({}, depthAtMost(4), 8), std::move(rays));
}

OctreeCase tinyComponents() {
  std::mt19937_64 rng(117);
  std::uniform_int_distribution<int64_t> small(-2, 2);
  std::vector<QRay> rays;
  for (int i = 0; i < 150; ++i) {
    QRay r{0, randomLatticePoint(rng), {small(rng), small(rng), small(rng)}};
    r.dir[i % 3] = (i & 8) ? -kDirMax : kDirMax;
    if (i % 4 == 0) r.dir[(i + 1) % 3] = (i & 16) ? -1 : 1;
    rays.push_back(r);
  }
  return makeCase("tiny_components",
                  fx::buildOctreeImage(quantizeScene(subdivide(makeCornellBox(), 1)), depthAtMost(7), 2),
                  std::move(rays));
}

OctreeCase cornellRandom() {
  const Scene scene = makeCornellBox();
  const Quantizer quantizer(scene.bounds);
  std::vector<QTriangle> tris = quantizer.quantize(scene);
  std::mt19937 rng(118);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::normal_distribution<float> n;
  const glm::vec3 lo = scene.bounds.lo - 0.5f * scene.bounds.diagonal();
  const glm::vec3 size = 2.0f * scene.bounds.diagonal();
  std::vector<QRay> rays;
  for (uint32_t i = 0; rays.size() < 300 && i < 3000; ++i) {
    Ray r;
    r.origin = lo + glm::vec3(u(rng), u(rng), u(rng)) * size;
    if (i % 2 == 0) {  // aimed at a point of a triangle
      const Triangle& t = scene.triangles[size_t(u(rng) * float(scene.size() - 1))];
      const float s = std::sqrt(u(rng)), w = u(rng);
      r.dir = (1.0f - s) * t.v0 + s * (1.0f - w) * t.v1 + s * w * t.v2 - r.origin;
    } else {
      r.dir = glm::vec3(n(rng), n(rng), n(rng));
    }
    if (glm::length(r.dir) < 1e-3f) continue;
    if (auto q = quantizer.quantize(r, i)) rays.push_back(q->q);
  }
  std::mt19937_64 rng64(119);
  addRandomRays(rays, rng64, 100);
  for (QRay& r : quantizedCamera(scene, 16, 16).rays) rays.push_back(r);
  const int depth = fx::defaultOctreeDepth(tris.size());
  return makeCase("cornell_random", fx::buildOctreeImage(std::move(tris), depth, fx::kDefaultOctreeLeafSize),
                  std::move(rays));
}

// Segment ends and any-hit: a wall on the root's mid-plane and one off every
// node boundary, walked both ways; bounded and any-hit variants of random and
// camera rays over the Cornell box.
std::vector<OctreeCase> segmentEnds() {
  std::vector<OctreeCase> cases;
  for (const auto& [name, zWall, zOrigin] : {std::tuple{"segment_wall_mid_plane", kMid, kPosMax / 16 + 3},
                                             std::tuple{"segment_wall_off_planes_minus_z", kPosMax / 5 + 1,
                                                        kPosMax - 7}}) {
    QuantizedScene wall = segmentScene(zWall, zOrigin);
    cases.push_back(makeCase(name, fx::buildOctreeImage(wall.triangles, depthAtMost(5), 1), std::move(wall.rays)));
  }
  std::vector<QTriangle> tris = quantizedCornell();
  std::mt19937_64 rng(29);
  std::vector<QRay> rays;
  addRandomRays(rays, rng, 60);
  for (QRay& r : quantizedCamera(makeCornellBox(), 8, 8).rays) rays.push_back(r);
  std::vector<QRay> variants = segmentVariants(tris, rays, rays.size());
  const int depth = fx::defaultOctreeDepth(tris.size());
  cases.push_back(makeCase("segment_variants_cornell",
                           fx::buildOctreeImage(std::move(tris), depth, fx::kDefaultOctreeLeafSize),
                           std::move(variants)));
  return cases;
}

}  // namespace

std::vector<OctreeCase> octreeHardCases() {
  std::vector<OctreeCase> cases = makeCases<OctreeCase>(
      {axisParallel, midPlanes, centreAndCorners, octants, nodeFaces, rootFaces, deepLeafOrigins,
       [] { return offCentre(false); }, [] { return offCentre(true); }, maxDepth, deepSparse, full, emptyLeaves,
       crowdedLeaf, rootLeaf, empty, tinyComponents, cornellRandom});
  for (OctreeCase& c : segmentEnds()) cases.push_back(std::move(c));
  return cases;
}

}  // namespace lancer::test
