#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <map>
#include <random>
#include <set>
#include <tuple>

#include <fmt/format.h>

#include "common/error.h"
#include "oracle/embree_accel.h"
#include "ref/benchmark.h"
#include "ref/brute_force.h"
#include "ref/bvh.h"
#include "ref/triangle.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "support/random_points.h"
#include "support/test_paths.h"

namespace lancer {
namespace {

// ---------------------------------------------------------------------------
// Helpers

const Scene& cachedScene(const std::string& name) {
  static std::map<std::string, Scene> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, loadScene(name)).first;
  return it->second;
}

const std::vector<std::string>& sceneNames() {
  static const std::vector<std::string> names = {kDefaultSceneName, test::kBunny, test::kWuson};
  return names;
}

std::string hex(const Ray& r) {
  return fmt::format("o=({:a},{:a},{:a}) d=({:a},{:a},{:a}) tMax={:a}", r.origin.x, r.origin.y, r.origin.z,
                     r.dir.x, r.dir.y, r.dir.z, r.tMax);
}

std::string hex(const std::optional<Hit>& h) {
  if (!h) return "miss";
  return fmt::format("prim={} t={:a} u={:a} v={:a}", h->prim, h->t, h->u, h->v);
}

bool identical(const std::optional<Hit>& a, const std::optional<Hit>& b) {
  if (a.has_value() != b.has_value()) return false;
  if (!a) return true;
  return a->prim == b->prim && std::bit_cast<uint32_t>(a->t) == std::bit_cast<uint32_t>(b->t) &&
         std::bit_cast<uint32_t>(a->u) == std::bit_cast<uint32_t>(b->u) &&
         std::bit_cast<uint32_t>(a->v) == std::bit_cast<uint32_t>(b->v);
}

// Compares the BVH with brute force ray by ray, bit for bit, and checks that
// intersectP and the stats-counting path answer the same. Prints the first few
// mismatches as hex reproducers.
class Agreement {
 public:
  Agreement(const Scene& scene, const Bvh& bvh, std::string label)
      : brute_(scene), bvh_(bvh), label_(std::move(label)) {}

  // Returns the BVH's hit for tests that need it.
  std::optional<Hit> check(const Ray& ray, const std::optional<Hit>* expected = nullptr) {
    const std::optional<Hit> want = expected ? *expected : brute_.intersect(ray);
    const std::optional<Hit> got = bvh_.intersect(ray);
    TraversalStats stats;
    const std::optional<Hit> counted = bvh_.intersect(ray, &stats);
    const bool any = bvh_.intersectP(ray);
    ++rays_;
    hits_ += got.has_value();
    if (!identical(got, want) || !identical(counted, want) || any != want.has_value()) {
      if (++mismatches_ <= 5) {
        ADD_FAILURE() << label_ << ": ray " << hex(ray) << "\n  bvh   " << hex(got) << "\n  brute " << hex(want)
                      << "\n  counted " << hex(counted) << " intersectP " << any;
      }
    }
    return got;
  }
  const BruteForce& brute() const { return brute_; }
  int rays() const { return rays_; }
  int hits() const { return hits_; }
  int mismatches() const { return mismatches_; }

 private:
  BruteForce brute_;
  const Bvh& bvh_;
  std::string label_;
  int rays_ = 0, hits_ = 0, mismatches_ = 0;
};

AccelOptions leafOptions(int leafSize) {
  AccelOptions options;
  options.bvhLeafSize = leafSize;
  return options;
}

// Runs body(name, scene, bvh, agree) on every test scene with leaves of 1 and
// 4 triangles, each against brute force; no ray may mismatch.
template <class Body>
void forEachSceneAndLeafSize(Body body) {
  for (const std::string& name : sceneNames()) {
    const Scene& scene = cachedScene(name);
    for (int leafSize : {1, 4}) {
      const Bvh bvh(scene, leafOptions(leafSize));
      Agreement agree(scene, bvh, fmt::format("{} leaf {}", name, leafSize));
      body(name, scene, bvh, agree);
      EXPECT_EQ(agree.mismatches(), 0) << name << " leaf " << leafSize;
    }
  }
}

CameraOptions resolution(int width, int height) {
  CameraOptions options;
  options.width = width;
  options.height = height;
  return options;
}

glm::vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  for (;;) {
    const glm::vec3 v(n(rng), n(rng), n(rng));
    const float len = glm::length(v);
    if (len > 1e-3f) return v / len;
  }
}

using test::randomIn;  // random_points.h

glm::vec3 randomOutside(const Aabb& b, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(1.2f, 3.0f);
  return b.center() + randomUnit(rng) * (0.5f * glm::length(b.diagonal()) * u(rng));
}

// ---------------------------------------------------------------------------
// Construction

TEST(Bvh, RejectsInvalidLeafSize) {
  const Scene& box = cachedScene(kDefaultSceneName);
  for (int size : {0, -1, 65, 1000}) {
    EXPECT_THROW(Bvh(box, leafOptions(size)), InputError) << size;
  }
  for (int size : {1, 64}) {
    EXPECT_NO_THROW(Bvh(box, leafOptions(size))) << size;
  }
  EXPECT_EQ(Bvh(box, {}).name(), "bvh");
}

TEST(Bvh, NodesFormAValidDepthFirstTree) {
  for (const std::string& name : sceneNames()) {
    const Scene& scene = cachedScene(name);
    for (int leafSize : {1, 4, 64}) {
      const Bvh bvh(scene, leafOptions(leafSize));
      const auto& nodes = bvh.nodes();
      ASSERT_EQ(nodes.size(), bvh.nodeCount());
      EXPECT_EQ(bvh.nodeCount(), 2 * bvh.leafCount() - 1) << name;
      EXPECT_LE(bvh.depth(), Bvh::kMaxDepth);
      // Every triangle appears in exactly one leaf.
      std::vector<uint32_t> ids = bvh.primIds();
      std::sort(ids.begin(), ids.end());
      ASSERT_EQ(ids.size(), scene.size());
      for (uint32_t i = 0; i < ids.size(); ++i) ASSERT_EQ(ids[i], i);
      // Walk the tree: children follow the depth-first rule, bounds are exact.
      int maxDepth = 0;
      std::vector<std::pair<uint32_t, int>> todo = {{0, 1}};
      size_t seen = 0;
      while (!todo.empty()) {
        auto [index, depth] = todo.back();
        todo.pop_back();
        ++seen;
        maxDepth = std::max(maxDepth, depth);
        const BvhNode& node = nodes[index];
        Aabb expect;
        if (node.isLeaf()) {
          ASSERT_LE(node.count, leafSize);
          for (uint32_t i = node.index; i < node.index + node.count; ++i) {
            expect.extend(scene.triangles[bvh.primIds()[i]].bounds());
          }
        } else {
          ASSERT_GT(node.index, index + 1);
          ASSERT_LT(node.axis, 3);
          expect.extend(Aabb{nodes[index + 1].lo, nodes[index + 1].hi});
          expect.extend(Aabb{nodes[node.index].lo, nodes[node.index].hi});
          todo.push_back({index + 1, depth + 1});
          todo.push_back({node.index, depth + 1});
        }
        ASSERT_EQ(node.lo, expect.lo) << "node " << index;
        ASSERT_EQ(node.hi, expect.hi) << "node " << index;
      }
      EXPECT_EQ(seen, nodes.size());
      EXPECT_EQ(maxDepth, bvh.depth());
    }
  }
}

TEST(Bvh, EmptySceneAndInvalidRaysMiss) {
  const Scene empty;
  const Bvh none(empty, {});
  EXPECT_EQ(none.nodeCount(), 0u);
  EXPECT_FALSE(none.intersect(Ray{}).has_value());
  EXPECT_FALSE(none.intersectP(Ray{}));

  const Bvh bvh(cachedScene(kDefaultSceneName), {});
  const Ray good{glm::vec3(278, 273, -800), glm::vec3(0, 0, 1)};
  ASSERT_TRUE(bvh.intersect(good).has_value());
  Ray zero = good;
  zero.dir = glm::vec3(0.0f, -0.0f, 0.0f);
  EXPECT_FALSE(bvh.intersect(zero).has_value());
  Ray nan = good;
  nan.dir.x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(bvh.intersectP(nan));
}

// ---------------------------------------------------------------------------
// Bit-identical agreement with brute force

TEST(Bvh, MatchesBruteForceOnRandomRays) {
  for (const std::string& name : sceneNames()) {
    const Scene& scene = cachedScene(name);
    std::mt19937 rng(1234);
    std::vector<Ray> rays;
    for (int i = 0; i < 1500; ++i) {  // from outside, aimed into the bounds
      const glm::vec3 o = randomOutside(scene.bounds, rng);
      rays.push_back(Ray{o, randomIn(scene.bounds, rng) - o});
    }
    for (int i = 0; i < 1500; ++i) {  // from inside, every octant
      rays.push_back(Ray{randomIn(scene.bounds, rng), randomUnit(rng)});
    }
    const BruteForce brute(scene);
    std::vector<std::optional<Hit>> expected;
    for (const Ray& r : rays) expected.push_back(brute.intersect(r));
    for (int leafSize : {1, 4, 64}) {
      const Bvh bvh(scene, leafOptions(leafSize));
      Agreement agree(scene, bvh, fmt::format("{} leaf {}", name, leafSize));
      for (size_t i = 0; i < rays.size(); ++i) agree.check(rays[i], &expected[i]);
      EXPECT_EQ(agree.mismatches(), 0) << name << " leaf " << leafSize;
      EXPECT_GT(agree.hits(), 300) << name;  // the rays are not all trivial misses
    }
  }
}

TEST(Bvh, MatchesBruteForceOnAxisParallelRaysWithSignedZeros) {
  forEachSceneAndLeafSize([](const std::string& name, const Scene& scene, const Bvh& bvh, Agreement& agree) {
    std::mt19937 rng(99);
    std::uniform_int_distribution<size_t> pickNode(0, bvh.nodeCount() - 1);
    std::uniform_int_distribution<size_t> pickTri(0, scene.size() - 1);
    std::uniform_int_distribution<int> coin(0, 1);
    for (int i = 0; i < 1200; ++i) {
      const int axis = i % 3;
      // Cross-axis coordinates: exactly on a node's bounds planes (where the
      // slab test meets 0 * inf), on a vertex, or anywhere in the bounds.
      const BvhNode& node = bvh.nodes()[pickNode(rng)];
      const Triangle& tri = scene.triangles[pickTri(rng)];
      glm::vec3 o = randomIn(scene.bounds, rng);
      for (int a = 0; a < 3; ++a) {
        if (a == axis) continue;
        switch ((i / 3) % 3) {
          case 0: o[a] = coin(rng) ? node.lo[a] : node.hi[a]; break;
          case 1: o[a] = tri.v0[a]; break;
          default: break;
        }
      }
      // Along the axis: outside the scene, inside it, or on a node plane.
      const bool negative = coin(rng);
      switch ((i / 9) % 3) {
        case 0: o[axis] = negative ? scene.bounds.hi[axis] + 1.0f : scene.bounds.lo[axis] - 1.0f; break;
        case 1: break;
        default: o[axis] = coin(rng) ? node.lo[axis] : node.hi[axis]; break;
      }
      glm::vec3 d(coin(rng) ? 0.0f : -0.0f, coin(rng) ? 0.0f : -0.0f, coin(rng) ? 0.0f : -0.0f);
      d[axis] = negative ? -1.0f : 1.0f;
      agree.check(Ray{o, d});
      // One zero component only: a ray in a coordinate plane.
      d[(axis + 1) % 3] = negative ? 0.37f : -0.61f;
      agree.check(Ray{o, d});
    }
    EXPECT_GT(agree.hits(), 100) << name;
  });
}

TEST(Bvh, MatchesBruteForceOnRaysAimedAtVerticesAndEdgeMidpoints) {
  forEachSceneAndLeafSize([](const std::string& name, const Scene& scene, const Bvh&, Agreement& agree) {
    std::mt19937 rng(7);
    const size_t step = std::max<size_t>(1, scene.size() / 150);
    for (size_t t = 0; t < scene.size(); t += step) {
      const Triangle& tri = scene.triangles[t];
      const std::array<glm::vec3, 6> targets = {tri.v0, tri.v1, tri.v2, 0.5f * (tri.v0 + tri.v1),
                                                 0.5f * (tri.v1 + tri.v2), 0.5f * (tri.v2 + tri.v0)};
      for (const glm::vec3& target : targets) {
        for (const glm::vec3& o : {randomOutside(scene.bounds, rng), randomIn(scene.bounds, rng)}) {
          agree.check(Ray{o, target - o});
        }
      }
    }
    EXPECT_GT(agree.hits(), agree.rays() / 2) << name;
  });
}

TEST(Bvh, MatchesBruteForceOnTMaxLimitedRays) {
  for (const std::string& name : sceneNames()) {
    const Scene& scene = cachedScene(name);
    const Bvh bvh(scene, {});
    Agreement agree(scene, bvh, name);
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> frac(0.0f, 1.5f);
    int limited = 0;
    while (limited < 300) {
      const glm::vec3 o = randomOutside(scene.bounds, rng);
      Ray ray{o, randomIn(scene.bounds, rng) - o};
      const std::optional<Hit> hit = agree.brute().intersect(ray);
      if (!hit) continue;
      ++limited;
      // Exactly at the hit, one ulp either side, and anywhere around it.
      for (float tMax : {hit->t, std::nextafter(hit->t, 0.0f), std::nextafter(hit->t, kInfinity),
                         hit->t * frac(rng), 0.0f}) {
        ray.tMax = tMax;
        agree.check(ray);
      }
    }
    EXPECT_EQ(agree.mismatches(), 0) << name;
  }
}

// Ties: identical or coplanar overlapping triangles in different leaves must
// resolve to the lowest id, as closerHit() says, whatever order the BVH visits.
TEST(Bvh, ExactTiesGoToTheLowestTriangleId) {
  Scene scene;
  const Triangle base{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)};
  for (int i = 0; i < 200; ++i) scene.triangles.push_back(base);  // all centroids coincide
  // Coplanar, overlapping, shifted so the centroids differ; id order opposite to x.
  for (int i = 0; i < 50; ++i) {
    const float dx = 0.01f * float(50 - i);
    scene.triangles.push_back(
        Triangle{glm::vec3(-0.5f + dx, -0.5f, 0), glm::vec3(1.5f + dx, -0.5f, 0), glm::vec3(dx, 1.5f, 0)});
  }
  scene.materialOf.assign(scene.size(), 0);
  scene.computeBounds();
  for (int leafSize : {1, 3, 64}) {
    const Bvh bvh(scene, leafOptions(leafSize));
    Agreement agree(scene, bvh, fmt::format("ties leaf {}", leafSize));
    std::mt19937 rng(3);
    for (int i = 0; i < 300; ++i) {
      const glm::vec3 target = randomIn(Aabb{glm::vec3(0.0f), glm::vec3(0.5f, 0.5f, 0.0f)}, rng);
      const glm::vec3 o = target + glm::vec3(0.3f, -0.2f, i % 2 ? 1.0f : -1.0f);
      const std::optional<Hit> hit = agree.check(Ray{o, target - o});
      ASSERT_TRUE(hit.has_value());
      EXPECT_EQ(hit->prim, 0u);
    }
    EXPECT_EQ(agree.mismatches(), 0);
  }
}

// Triangles spaced and sized geometrically along x: SAH peels a few off the far
// end per level, the deepest kind of tree it builds. Coordinates stay below
// 1e15 so the triangle test's products cannot overflow.
TEST(Bvh, GeometricChainStaysWithinTheDepthBound) {
  Scene scene;
  float x = 1.0f;
  for (int i = 0; i < 100; ++i, x *= 1.4f) {
    const float size = 0.2f * x;
    scene.triangles.push_back(Triangle{glm::vec3(x, -size, -size), glm::vec3(x, size, -size),
                                       glm::vec3(x + size, 0, size)});
  }
  scene.materialOf.assign(scene.size(), 0);
  scene.computeBounds();
  const Bvh bvh(scene, leafOptions(1));
  EXPECT_LE(bvh.depth(), Bvh::kMaxDepth);
  EXPECT_GT(bvh.depth(), 15);  // far deeper than a balanced tree (7 levels): a chain
  Agreement agree(scene, bvh, "chain");
  std::mt19937 rng(11);
  for (int i = 0; i < 500; ++i) {
    // From the origin side towards one triangle, and back along the axis.
    const Triangle& t = scene.triangles[size_t(i) % scene.size()];
    const glm::vec3 target = (t.v0 + t.v1 + t.v2) / 3.0f;
    const glm::vec3 o = i % 2 ? glm::vec3(-1.0f, 0.3f, -0.2f) : target * 2.0f + glm::vec3(0, 0.1f, 0);
    agree.check(Ray{o, target - o + 0.01f * glm::length(target - o) * randomUnit(rng)});
  }
  EXPECT_EQ(agree.mismatches(), 0);
  EXPECT_GT(agree.hits(), 250);
}

// ---------------------------------------------------------------------------
// Watertightness on closed meshes built here, with bit-identical shared vertices.

// The library's icosphere off the unit sphere and off the origin, so the
// coordinates are not "nice" (a vertex's copies still map to the same bits).
Scene offsetIcosphere(int levels) {
  Scene scene = makeIcosphere(levels);
  const auto at = [](const glm::vec3& p) { return glm::vec3(3.1f, -1.7f, 0.45f) + p * glm::vec3(1.3f, 0.9f, 1.7f); };
  for (Triangle& t : scene.triangles) t = {at(t.v0), at(t.v1), at(t.v2)};
  scene.computeBounds();
  return scene;
}

// An octahedron subdivided with lancer's subdivide(): many coplanar neighbours,
// the classic place for a crack to open.
Scene makeSubdividedOctahedron(int levels) {
  const glm::vec3 c(-2.3f, 0.7f, 5.1f);
  const glm::vec3 x(1.37f, 0, 0), y(0, 0.83f, 0), z(0, 0, 2.11f);
  Scene scene;
  scene.name = "octahedron";
  for (const glm::vec3& sx : {x, -x})
    for (const glm::vec3& sy : {y, -y})
      for (const glm::vec3& sz : {z, -z}) scene.triangles.push_back(Triangle{c + sx, c + sy, c + sz});
  scene.materialOf.assign(scene.size(), 0);
  scene.materials.push_back(Material{});
  scene.computeBounds();
  return subdivide(scene, levels);
}

TEST(Bvh, ClosedMeshesDoNotLeakAtSharedEdgesOrVertices) {
  const std::vector<std::pair<Scene, glm::vec3>> meshes = {
      {offsetIcosphere(3), glm::vec3(3.1f, -1.7f, 0.45f)}, {makeSubdividedOctahedron(3), glm::vec3(-2.3f, 0.7f, 5.1f)}};
  for (const auto& [scene, centre] : meshes) {
    // Every distinct vertex and every distinct edge's midpoint (0.5f (a + b) is
    // symmetric, so it is the same point whichever triangle computes it).
    std::set<std::tuple<float, float, float>> targets;
    auto add = [&](const glm::vec3& p) { targets.insert({p.x, p.y, p.z}); };
    for (const Triangle& t : scene.triangles) {
      for (const glm::vec3& p : {t.v0, t.v1, t.v2, 0.5f * (t.v0 + t.v1), 0.5f * (t.v1 + t.v2),
                                 0.5f * (t.v2 + t.v0)}) {
        add(p);
      }
    }
    for (int leafSize : {1, 4}) {
      const Bvh bvh(scene, leafOptions(leafSize));
      Agreement agree(scene, bvh, fmt::format("{} leaf {}", scene.name, leafSize));
      int leaks = 0;
      for (const auto& [px, py, pz] : targets) {
        const glm::vec3 p(px, py, pz);
        // From the centre, from an off-centre interior point, and from outside
        // along the line through the centre (which crosses the surface at p).
        const std::array<glm::vec3, 3> origins = {centre, centre + glm::vec3(0.11f, -0.07f, 0.05f),
                                                  centre + 3.0f * (p - centre)};
        for (const glm::vec3& o : origins) {
          const Ray ray{o, p - o};
          const bool hit = agree.check(ray).has_value();
          if (!hit && ++leaks <= 5) ADD_FAILURE() << scene.name << " leak: " << hex(ray);
        }
      }
      EXPECT_EQ(leaks, 0) << scene.name << " leaf " << leafSize << " over " << agree.rays() << " rays";
      EXPECT_EQ(agree.mismatches(), 0);
      EXPECT_GT(targets.size(), 600u);
    }
  }
}

TEST(Bvh, StatsCountTheWorkDone) {
  const Scene& bunny = cachedScene(test::kBunny);
  const Bvh bvh(bunny, {});
  const auto rays = frameScene(bunny, resolution(32, 32)).generateRays();
  TraversalStats stats;
  for (const Ray& r : rays) bvh.intersect(r, &stats);
  EXPECT_GT(stats.nodesVisited, rays.size() / 2);
  EXPECT_GT(stats.triangleTests, 0u);
  // Far fewer tests than brute force's rays * triangles.
  EXPECT_LT(stats.triangleTests, rays.size() * bunny.size() / 50);
}

// ---------------------------------------------------------------------------
// The benchmark library (correctness only: nothing here is timed).

TEST(BvhBenchmark, ReportsHitsChecksumsAndAgreement) {
  const Scene& box = cachedScene(kDefaultSceneName);
  const auto rays = frameScene(box, resolution(48, 32)).generateRays();
  const Bvh bvh(box, {});
  const BruteForce brute(box);
  const EmbreeAccel embree(box);
  int calls = 0, lastDone = 0;
  BenchOptions options;
  options.repetitions = 3;
  options.progress = [&](const std::string&, int, int done, int total) {
    ++calls;
    lastDone = done;
    EXPECT_EQ(total, 9);
  };
  const BenchReport report =
      runBenchmark(box, rays, std::vector<BenchSubject>{{"bvh", &bvh, 0.5}, {"brute", &brute, {}}, {"embree", &embree, {}}},
                   options);
  EXPECT_EQ(calls, 9);
  EXPECT_EQ(lastDone, 9);
  EXPECT_EQ(report.rays, rays.size());
  EXPECT_EQ(report.triangles, box.size());
  ASSERT_EQ(report.results.size(), 3u);
  const BenchResult& first = report.results[0];
  const BenchResult& second = report.results[1];
  EXPECT_EQ(first.name, "bvh");
  EXPECT_EQ(first.buildSeconds, 0.5);
  EXPECT_FALSE(second.buildSeconds.has_value());
  EXPECT_EQ(first.hits, second.hits);
  EXPECT_EQ(first.checksum, second.checksum);  // bit-identical hit lists
  EXPECT_EQ(second.identical, rays.size());
  EXPECT_EQ(first.identical, rays.size());
  EXPECT_EQ(report.results[2].sameHitMiss, rays.size());  // the closed box: every ray hits
  EXPECT_EQ(report.results[2].agreeing, rays.size());
  for (const BenchResult& r : report.results) {
    EXPECT_TRUE(r.deterministic);
    ASSERT_EQ(r.mraysPerSecond.size(), 3u);
    ASSERT_EQ(r.cpuMraysPerSecond.size(), 3u);
    EXPECT_LE(r.minMraysPerSecond, r.medianMraysPerSecond);
    EXPECT_LE(r.medianMraysPerSecond, r.maxMraysPerSecond);
    EXPECT_GT(r.minMraysPerSecond, 0.0);
    EXPECT_GT(r.medianCpuMraysPerSecond, 0.0);
  }
}

TEST(BvhBenchmark, BuildsCandidatesAndRejectsBadInput) {
  const Scene& box = cachedScene(kDefaultSceneName);
  const auto rays = frameScene(box, resolution(8, 8)).generateRays();
  BenchOptions one;
  one.repetitions = 1;
  const BenchReport report = runBenchmark(
      box, rays, std::vector<BenchCandidate>{{"bvh", [&] { return std::make_unique<Bvh>(box, AccelOptions{}); }}}, one);
  ASSERT_EQ(report.results.size(), 1u);
  ASSERT_TRUE(report.results[0].buildSeconds.has_value());
  EXPECT_GE(*report.results[0].buildSeconds, 0.0);
  EXPECT_EQ(report.results[0].hits, rays.size());

  EXPECT_THROW(runBenchmark(box, rays, std::vector<BenchSubject>{}), InputError);
  EXPECT_THROW(runBenchmark(box, rays, std::vector<BenchSubject>{{"null", nullptr, {}}}), InputError);
  const Bvh bvh(box, {});
  BenchOptions zero;
  zero.repetitions = 0;
  EXPECT_THROW(runBenchmark(box, rays, std::vector<BenchSubject>{{"bvh", &bvh, {}}}, zero), InputError);
}

// ---------------------------------------------------------------------------
// Throughput measurement for docs/performance.md. Disabled: nothing timed runs
// in the suite. Run with
//   lancer_unit_tests --gtest_also_run_disabled_tests --gtest_filter='BvhPerf.*'
// and LANCER_PERF_SCENE=<file> LANCER_PERF_SUBDIVIDE=<k> LANCER_PERF_REPS=<n>.
TEST(BvhPerf, DISABLED_PrimaryRayThroughput) {
  auto env = [](const char* name, const char* fallback) {
    const char* value = std::getenv(name);
    return std::string(value ? value : fallback);
  };
  const Scene scene = subdivide(loadScene(env("LANCER_PERF_SCENE", test::kBunny.c_str())),
                                std::stoi(env("LANCER_PERF_SUBDIVIDE", "0")));
  const auto rays = frameScene(scene, CameraOptions{}).generateRays();  // 512 x 512
  AccelOptions accelOptions;
  accelOptions.bvhLeafSize = std::stoi(env("LANCER_PERF_LEAF", "4"));
  const std::vector<BenchCandidate> candidates = {
      {"bvh", [&] { return std::make_unique<Bvh>(scene, accelOptions); }},
      {"embree", [&] { return std::make_unique<EmbreeAccel>(scene); }}};
  BenchOptions options;
  options.repetitions = std::stoi(env("LANCER_PERF_REPS", "5"));
  const BenchReport report = runBenchmark(scene, rays, candidates, options);
  fmt::print("scene {} triangles {} rays {} repetitions {}\n", scene.name, report.triangles, report.rays,
             report.repetitions);
  for (const BenchResult& r : report.results) {
    fmt::print("  {:7} build {:.3f} s  median {:.2f} Mrays/s  [{:.2f}, {:.2f}]  cpu-time median {:.2f}  hits {}  "
               "agreeing {}  identical {}\n",
               r.name, *r.buildSeconds, r.medianMraysPerSecond, r.minMraysPerSecond, r.maxMraysPerSecond,
               r.medianCpuMraysPerSecond, r.hits, r.agreeing, r.identical);
  }
  fmt::print("  bvh/embree {:.3f}\n", report.results[0].medianMraysPerSecond / report.results[1].medianMraysPerSecond);
}

}  // namespace
}  // namespace lancer
