// The Verilated rt_grid against the golden grid model (fx::traverseGrid): for
// every ray the same cells in the same order, the same number of tests and the
// same closest hit, bit for bit, under memory latency jitter, output
// backpressure and input bubbles.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>

#include <fmt/format.h>

#include "common/error.h"
#include "driver/traversal_device.h"
#include "driver/quantize.h"
#include "driver/verilator_grid_device.h"
#include "golden/isect.h"
#include "scene/camera.h"
#include "scene/scene.h"

namespace lancer {
namespace {

using fx::GridImage;
using fx::GridRes;
using fx::kDirMax;
using fx::kPosBits;
using fx::kPosMax;
using fx::QRay;
using fx::QTriangle;

VerilatorGridDevice& rtl() {
  static VerilatorGridDevice device;
  return device;
}

std::string hex(const QRay& r) {
  return fmt::format("ray {} org ({:#x}, {:#x}, {:#x}) dir ({}, {}, {})", r.id, r.org[0], r.org[1], r.org[2],
                     r.dir[0], r.dir[1], r.dir[2]);
}

std::string describe(const fx::GridTrace& t) {
  std::string s = fmt::format("{} cells [", t.visits.size());
  for (size_t i = 0; i < std::min<size_t>(t.visits.size(), 12); ++i) s += fmt::format("{} ", t.visits[i]);
  if (t.visits.size() > 12) s += "...";
  s += fmt::format("] tests {} ", t.tests);
  if (t.hit) {
    s += fmt::format("hit prim {} t_num {:#x} det {:#x}", t.hit->primId, uint64_t(t.hit->tNum),
                     uint64_t(t.hit->det));
  } else {
    s += "miss";
  }
  return s;
}

// Runs both devices, expects equal traces per ray; returns the RTL's stats.
TraversalRunStats expectSameTraces(const GridImage& image, const std::vector<QRay>& rays, const TraversalRunOptions& options) {
  GoldenGridDevice golden;
  std::vector<fx::GridTrace> want, got;
  const TraversalRunStats g = golden.run(image, rays, want, options);
  const TraversalRunStats r = rtl().run(image, rays, got, options);
  EXPECT_EQ(got.size(), want.size());
  int reported = 0;
  for (size_t k = 0; k < std::min(got.size(), want.size()); ++k) {
    if (got[k] == want[k]) continue;
    ADD_FAILURE() << "grid " << image.res[0] << "x" << image.res[1] << "x" << image.res[2] << ", " << hex(rays[k])
                  << "\n  rtl:    " << describe(got[k]) << "\n  golden: " << describe(want[k]);
    if (++reported == 5) break;
  }
  EXPECT_EQ(r.steps, g.steps);
  EXPECT_EQ(r.nodeReads, g.nodeReads);
  EXPECT_EQ(r.indexReads, g.indexReads);
  EXPECT_EQ(r.triangleReads, g.triangleReads);
  EXPECT_EQ(r.isectTests, g.isectTests);
  EXPECT_EQ(r.rays, rays.size());
  EXPECT_TRUE(r.cycleAccurate);
  return r;
}

// Adverse conditions: memory jitter, output stalls, input bubbles.
TraversalRunOptions rough(uint64_t seed, int raysInFlight = 0) {
  TraversalRunOptions o;
  o.memLatency = 7;
  o.memLatencyJitter = 13;
  o.raysInFlight = raysInFlight;
  o.stream.outputStallProbability = 0.3;
  o.stream.inputIdleProbability = 0.2;
  o.stream.seed = seed;
  return o;
}

QRay normalized(QRay r) {
  const int k = fx::dominantAxis(r.dir);
  r.dir[k] = r.dir[k] < 0 ? -kDirMax : kDirMax;
  return r;
}

QRay randomRay(std::mt19937_64& rng, uint32_t id) {
  std::uniform_int_distribution<int64_t> pos(0, kPosMax), dir(-kDirMax, kDirMax);
  return normalized(QRay{id, {pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng)}});
}

// Random triangles with vertices within `spread` lattice units of a random centre.
std::vector<QTriangle> randomTriangles(std::mt19937_64& rng, int count, int64_t spread) {
  std::uniform_int_distribution<int64_t> pos(0, kPosMax), off(-spread, spread);
  std::vector<QTriangle> tris;
  for (int i = 0; i < count; ++i) {
    QTriangle t;
    t.id = uint32_t(i);
    const std::array<int64_t, 3> c{pos(rng), pos(rng), pos(rng)};
    for (auto& v : t.v)
      for (int a = 0; a < 3; ++a) v[a] = std::clamp<int64_t>(c[a] + off(rng), 0, kPosMax);
    tris.push_back(t);
  }
  return tris;
}

const Scene& bunny() {
  static const Scene scene = loadScene(std::string(LANCER_DATA_DIR) + "/scenes/bunny.obj");
  return scene;
}

struct QuantizedScene {
  std::vector<QTriangle> triangles;
  std::vector<QRay> rays;
};

// Camera rays of the bunny through the quantizer, as the driver makes them.
QuantizedScene bunnyCamera(int width, int height) {
  const Scene& scene = bunny();
  const Quantizer quantizer(scene.bounds);
  QuantizedScene q;
  for (uint32_t i = 0; i < scene.size(); ++i) q.triangles.push_back(quantizer.quantize(scene.triangles[i], i));
  CameraOptions camera;
  camera.width = width;
  camera.height = height;
  const std::vector<Ray> rays = frameScene(scene, camera).generateRays();
  for (uint32_t i = 0; i < rays.size(); ++i) {
    if (auto r = quantizer.quantize(rays[i], i)) q.rays.push_back(r->q);
  }
  return q;
}

TEST(RtGrid, BunnyCameraRays) {
  const QuantizedScene q = bunnyCamera(40, 40);
  const GridImage image = fx::buildGridImage(q.triangles, fx::chooseGridResolution(q.triangles));
  expectSameTraces(image, q.rays, rough(1));
}

TEST(RtGrid, BunnyRandomRaysAtSeveralResolutions) {
  const QuantizedScene q = bunnyCamera(1, 1);
  std::mt19937_64 rng(2);
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < 400; ++i) rays.push_back(randomRay(rng, i));
  for (const GridRes& res : {GridRes{1, 1, 1}, GridRes{3, 7, 5}, GridRes{32, 32, 32}}) {
    SCOPED_TRACE(fmt::format("{}x{}x{}", res[0], res[1], res[2]));
    // One cell tests every triangle per ray: fewer rays there keep the runtime down.
    const std::vector<QRay> some(rays.begin(), rays.begin() + (res[0] == 1 ? 60 : 400));
    expectSameTraces(fx::buildGridImage(q.triangles, res), some, rough(3 + res[0]));
  }
}

// Axis-parallel float rays with +0 and -0 components, through the quantizer.
TEST(RtGrid, AxisParallelRaysWithSignedZeros) {
  const Scene& scene = bunny();
  const Quantizer quantizer(scene.bounds);
  const QuantizedScene q = bunnyCamera(1, 1);
  const GridImage image = fx::buildGridImage(q.triangles, {16, 16, 16});
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<QRay> rays;
  const glm::vec3 lo = scene.bounds.lo, hi = scene.bounds.hi;
  for (uint32_t i = 0; i < 300; ++i) {
    const int axis = int(i % 3);
    Ray r;
    for (int a = 0; a < 3; ++a) r.origin[a] = lo[a] + (hi[a] - lo[a]) * u(rng);
    r.origin[axis] = (i & 8) ? hi[axis] + 1.0f : lo[axis] - 1.0f;
    r.dir = glm::vec3((i & 1) ? -0.0f : 0.0f, (i & 2) ? -0.0f : 0.0f, (i & 4) ? -0.0f : 0.0f);
    r.dir[axis] = (i & 8) ? -1.0f : 1.0f;
    if (auto qr = quantizer.quantize(r, i)) rays.push_back(qr->q);
  }
  ASSERT_GT(rays.size(), 100u);
  expectSameTraces(image, rays, rough(5));
}

// A 16^3 grid whose boundaries lie on lattice points (2^P / 16 apart): rays in
// the planes between voxels, along voxel edges, through corners, from the grid faces.
TEST(RtGrid, BoundaryPlanesEdgesCornersAndFaces) {
  std::mt19937_64 rng(6);
  const GridImage image = fx::buildGridImage(randomTriangles(rng, 300, kPosMax / 12), {16, 16, 16});
  const int64_t cell = int64_t(1) << (kPosBits - 4);
  std::uniform_int_distribution<int64_t> pick(0, 16), pos(0, kPosMax), dir(-kDirMax, kDirMax);
  auto boundary = [&] { return std::min(pick(rng) * cell, kPosMax); };
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < 600; ++i) {
    QRay r{i, {pos(rng), pos(rng), pos(rng)}, {dir(rng), dir(rng), dir(rng)}};
    switch (i % 6) {
      case 0:  // in a plane between voxels, moving within it
        r.org[i % 3] = boundary();
        r.dir[i % 3] = 0;
        break;
      case 1:  // along a voxel edge
        r.org[i % 3] = boundary();
        r.org[(i + 1) % 3] = boundary();
        r.dir[i % 3] = 0;
        r.dir[(i + 1) % 3] = 0;
        break;
      case 2:  // from a voxel corner along a diagonal (exact ties on all axes)
        for (int a = 0; a < 3; ++a) {
          r.org[a] = boundary();
          r.dir[a] = (dir(rng) < 0 ? -1 : 1) * kDirMax;
        }
        break;
      case 3:  // on a grid face
        r.org[i % 3] = (i & 1) ? 0 : kPosMax;
        break;
      case 4:  // from a corner of the grid
        for (int a = 0; a < 3; ++a) r.org[a] = (dir(rng) < 0) ? 0 : kPosMax;
        break;
      default:  // one component too small to ever step
        r.dir[i % 3] = (i & 1) ? 1 : -1;
        break;
    }
    if (r.dir == std::array<int64_t, 3>{0, 0, 0}) r.dir[0] = kDirMax;
    rays.push_back(normalized(r));
  }
  expectSameTraces(image, rays, rough(7));
}

TEST(RtGrid, OneCellGridAndFineGrid) {
  std::mt19937_64 rng(8);
  const std::vector<QTriangle> tris = randomTriangles(rng, 40, kPosMax / 6);
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < 60; ++i) rays.push_back(randomRay(rng, i));
  expectSameTraces(fx::buildGridImage(tris, {1, 1, 1}), rays, rough(9));
  expectSameTraces(fx::buildGridImage(tris, {256, 256, 256}), rays, rough(10));
}

// Mostly empty cells; triangles spanning many cells.
TEST(RtGrid, EmptyCellsAndLargeTriangles) {
  std::mt19937_64 rng(11);
  std::vector<QTriangle> tris = randomTriangles(rng, 6, kPosMax / 64);
  const std::vector<QTriangle> big = randomTriangles(rng, 6, kPosMax);
  for (QTriangle t : big) {
    t.id = uint32_t(tris.size());
    tris.push_back(t);
  }
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < 300; ++i) rays.push_back(randomRay(rng, i));
  expectSameTraces(fx::buildGridImage(tris, {64, 48, 40}), rays, rough(12));
}

// Thousands of triangles in one cell; rays through it and around it.
TEST(RtGrid, CrowdedCell) {
  std::mt19937_64 rng(13);
  std::uniform_int_distribution<int64_t> in(kPosMax / 4 + 2, kPosMax / 2 - 2);
  std::vector<QTriangle> tris;
  for (uint32_t i = 0; i < 3000; ++i) {
    QTriangle t;
    t.id = i;
    for (auto& v : t.v)
      for (auto& c : v) c = in(rng);
    tris.push_back(t);
  }
  const GridImage image = fx::buildGridImage(tris, {4, 4, 4});
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < 24; ++i) {
    QRay r = randomRay(rng, i);
    if (i % 2 == 0) r.org = {in(rng), in(rng), in(rng)};  // starts in the crowded cell
    rays.push_back(r);
  }
  expectSameTraces(image, rays, rough(14));
}

TEST(RtGrid, OneRayInFlightAndAllSlots) {
  const QuantizedScene q = bunnyCamera(12, 12);
  const GridImage image = fx::buildGridImage(q.triangles, fx::chooseGridResolution(q.triangles));
  expectSameTraces(image, q.rays, rough(15, 1));
  expectSameTraces(image, q.rays, rough(16, rtl().maxRaysInFlight()));
  TraversalRunOptions fast;  // no jitter, no stalls, latency 1
  fast.memLatency = 1;
  expectSameTraces(image, q.rays, fast);
}

TEST(RtGrid, RejectsTooManyRaysInFlight) {
  const GridImage image = fx::buildGridImage({}, {1, 1, 1});
  std::vector<fx::GridTrace> traces;
  TraversalRunOptions o;
  o.raysInFlight = rtl().maxRaysInFlight() + 1;
  try {
    rtl().run(image, std::vector<QRay>{QRay{0, {0, 0, 0}, {kDirMax, 0, 0}}}, traces, o);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(std::to_string(o.raysInFlight)), std::string::npos) << what;
    EXPECT_NE(what.find(std::to_string(rtl().maxRaysInFlight())), std::string::npos) << what;
  }
  o.raysInFlight = -1;
  EXPECT_THROW(rtl().run(image, std::vector<QRay>{}, traces, o), InputError);
}

TEST(RtGrid, WritesAnFstWaveformWhenAsked) {
  std::mt19937_64 rng(17);
  const GridImage image = fx::buildGridImage(randomTriangles(rng, 20, kPosMax / 4), {4, 4, 4});
  std::vector<QRay> rays;
  for (uint32_t i = 0; i < 8; ++i) rays.push_back(randomRay(rng, i));
  TraversalRunOptions o = rough(18);
  o.stream.wavePath = ::testing::TempDir() + "rt_grid_wave.fst";
  std::remove(o.stream.wavePath.c_str());
  expectSameTraces(image, rays, o);
  std::FILE* f = std::fopen(o.stream.wavePath.c_str(), "rb");
  ASSERT_NE(f, nullptr) << o.stream.wavePath;
  std::fseek(f, 0, SEEK_END);
  EXPECT_GT(std::ftell(f), 1000);
  std::fclose(f);
  std::remove(o.stream.wavePath.c_str());
}

// Performance sweep, not a check (docs/grid-unit.md has the table). Run with
//   build/tests/rtl/rtl_grid_tests --gtest_also_run_disabled_tests --gtest_filter='*Sweep*'
// LANCER_GRID_SWEEP_SIZE sets the image side (default 256).
TEST(RtGrid, DISABLED_Sweep) {
  const char* sizeEnv = std::getenv("LANCER_GRID_SWEEP_SIZE");
  const int side = sizeEnv ? std::atoi(sizeEnv) : 256;
  const QuantizedScene q = bunnyCamera(side, side);
  const GridImage image = fx::buildGridImage(q.triangles, fx::chooseGridResolution(q.triangles));
  fmt::print("bunny {} tris, grid {}x{}x{}, {} camera rays ({}x{})\n", q.triangles.size(), image.res[0],
             image.res[1], image.res[2], q.rays.size(), side, side);
  fmt::print("{:>6} {:>7} {:>10} {:>9} {:>11} {:>10} {:>13} {:>11}\n", "slots", "latency", "cycles", "tests/cyc",
             "steps/cyc", "isect busy", "Mrays/s@500M", "host ray/s");
  auto one = [&](int slots, int latency) {
    TraversalRunOptions o;
    o.memLatency = latency;
    o.raysInFlight = slots;
    std::vector<fx::GridTrace> traces;
    const auto start = std::chrono::steady_clock::now();
    const TraversalRunStats st = rtl().run(image, q.rays, traces, o);
    const double host = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double c = double(st.cycles);
    fmt::print("{:>6} {:>7} {:>10} {:>9.3f} {:>11.3f} {:>9.1f}% {:>13.2f} {:>11.0f}\n", slots, latency, st.cycles,
               double(st.isectTests) / c, double(st.steps) / c, 100.0 * double(st.isectBusyCycles) / c,
               double(st.rays) / c * 500.0, double(st.rays) / host);
  };
  const int max = rtl().maxRaysInFlight();
  for (int slots : {1, 4, 8, 16, 32}) {
    if (slots <= max) one(slots, 20);
  }
  for (int latency : {1, 10, 50, 100}) one(max, latency);
}

}  // namespace
}  // namespace lancer
