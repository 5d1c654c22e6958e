// The sweep's pieces that need no build tree: widths, specs, plans, and the
// crack rays, which must all hit a closed mesh through this build's golden
// pipeline (the watertightness claim of docs/number-formats.md, at this width).
#include <set>

#include <gtest/gtest.h>

#include "common/error.h"
#include "golden/isect.h"
#include "driver/cracks.h"
#include "sweep/spec.h"

namespace lancer::sweep {
namespace {

// An octahedron subdivided: closed, every edge shared by two triangles.
Scene closedMesh() {
  Scene s;
  s.name = "octahedron";
  const glm::vec3 px{1, 0, 0}, nx{-1, 0, 0}, py{0, 1.3f, 0}, ny{0, -0.7f, 0}, pz{0, 0, 0.9f}, nz{0, 0, -1.1f};
  for (const glm::vec3& y : {py, ny}) {
    const bool up = y.y > 0;
    s.triangles.push_back(up ? Triangle{px, y, pz} : Triangle{px, pz, y});
    s.triangles.push_back(up ? Triangle{pz, y, nx} : Triangle{pz, nx, y});
    s.triangles.push_back(up ? Triangle{nx, y, nz} : Triangle{nx, nz, y});
    s.triangles.push_back(up ? Triangle{nz, y, px} : Triangle{nz, px, y});
  }
  s.materials.push_back(Material{});
  s.materialOf.assign(s.triangles.size(), 0);
  s.computeBounds();
  return subdivide(s, 4);
}

TEST(Sweep, WidthsParseAndStayWithinTheFormats) {
  EXPECT_EQ(parseWidth("10/12", "t"), (Width{10, 12}));
  EXPECT_EQ(parseWidth("8", "t"), (Width{8, 8}));
  EXPECT_EQ(parseWidth("24/4", "t").name(), "24/4");
  EXPECT_EQ(parseWidth("6/6", "t"), (Width{6, 6}));
  EXPECT_EQ(parseWidth("5/7", "t"), (Width{5, 7}));
  for (const char* bad : {"3/10", "10/25", "0", "x/8", "8/", "/8", "8/8/8", "4/12", "6/5", "4"}) {
    EXPECT_THROW(parseWidth(bad, "--widths"), InputError) << bad;
  }
  try {
    parseWidth("3/10", "--widths");
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--widths: width 3/10: 3 bits lies outside what the formats admit (4..24)");
  }
}

TEST(Sweep, SpecRejectsUnknownUnitsAndModels) {
  Spec s;
  s.widths = {{8, 8}};
  s.scenes = {"builtin:cornell"};
  s.units = {"isect", "kdtree"};
  EXPECT_THROW(s.validate(), InputError);
  s.units = {"grid"};
  s.models = {"golden", "verilog"};
  EXPECT_THROW(s.validate(), InputError);
  s.models = {"golden"};
  EXPECT_NO_THROW(s.validate());
  s.widths = {{8, 8}, {8, 8}};
  EXPECT_THROW(s.validate(), InputError);
  EXPECT_THROW(Spec::fromJson({{"widths", {"8/8"}}, {"colour", 1}}, "spec.json"), InputError);
}

TEST(Sweep, PlanHasOneJobPerWidthUnitModelSceneAndRaySet) {
  Spec s;
  s.widths = {{8, 8}, {12, 10}};
  s.scenes = {"a.obj", "builtin:cornell"};
  s.units = {"isect", "octree"};
  s.models = {"golden", "rtl"};
  s.chunks = 3;
  s.crackRays = 16;
  const std::vector<Job> plan = makePlan(s);
  EXPECT_EQ(plan.size(), 2u * 2 * 2 * 2 * (3 + 1));
  std::set<std::string> keys;
  for (const Job& j : plan) {
    keys.insert(j.key);
    EXPECT_EQ(Job::fromJson(j.toJson()).key, j.key);
  }
  EXPECT_EQ(keys.size(), plan.size());
  EXPECT_TRUE(keys.count("w12-10.octree.rtl.s1.c2of3"));
  EXPECT_TRUE(keys.count("w8-8.isect.golden.s0.cracks"));
  EXPECT_EQ(sceneTag(s, 1), "s1-cornell");
}

// The quadric unit is rt_quadric beside rt_isect on native spheres and cones:
// no crack rays (they aim at shared triangle edges) and no structure walk.
TEST(Sweep, QuadricUnitRunsNativeQuadricsWithoutCrackRays) {
  Spec s;
  s.widths = {{10, 10}};
  s.scenes = {"builtin:spd-balls@1"};
  s.units = {"quadric", "bvh"};
  s.models = {"golden"};
  s.crackRays = 16;
  EXPECT_NO_THROW(s.validate());
  std::set<std::string> keys;
  for (const Job& j : makePlan(s)) keys.insert(j.key);
  EXPECT_EQ(keys, (std::set<std::string>{"w10-10.quadric.golden.s0.c0of1", "w10-10.bvh.golden.s0.c0of1",
                                         "w10-10.bvh.golden.s0.cracks"}));
  EXPECT_EQ(runUnitArgs("quadric"), (std::vector<std::string>{"--accel", "isect", "--quadrics", "native"}));
  EXPECT_EQ(runUnitArgs("octree"), (std::vector<std::string>{"--accel", "octree", "--quadrics", "tessellate"}));
  EXPECT_EQ(quadricFormArgs("isect"), (std::vector<std::string>{"--quadrics", "tessellate"}));
  EXPECT_EQ(synthTopOf("quadric"), "rt_quadric");
  EXPECT_FALSE(isTraversalUnit("quadric"));
  EXPECT_FALSE(isTraversalUnit("isect"));
  EXPECT_TRUE(isTraversalUnit("grid"));
}

TEST(Sweep, CrackRaysAllHitAClosedMeshOnThisLattice) {
  const Scene scene = closedMesh();
  const Quantizer quantizer(scene.bounds);
  const CrackRays c = makeCrackRays(scene, quantizer, 400, 7);
  ASSERT_EQ(c.rays.size(), 400u);
  EXPECT_EQ(c.edgeRays + c.vertexRays, c.rays.size());
  EXPECT_GT(c.vertexRays, 0u);
  EXPECT_EQ(c.rejected, 0u);
  const std::vector<fx::QTriangle> tris = quantizer.quantize(scene);
  for (size_t i = 0; i < c.rays.size(); ++i) {
    const std::optional<QuantizedRay> q = quantizer.quantize(c.rays[i], uint32_t(i));
    ASSERT_TRUE(q) << "ray " << i;
    bool hit = false;
    for (const fx::QTriangle& t : tris) hit = hit || fx::intersect(q->q, t).hit;
    EXPECT_TRUE(hit) << "crack at ray " << i;
  }
  // The same seed gives the same rays.
  const CrackRays again = makeCrackRays(scene, quantizer, 400, 7);
  for (size_t i = 0; i < c.rays.size(); ++i) EXPECT_EQ(again.rays[i].origin, c.rays[i].origin);
}

}  // namespace
}  // namespace lancer::sweep
