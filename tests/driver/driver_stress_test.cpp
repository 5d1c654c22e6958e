// The stability suite (sw/stress, docs/stability.md): its cases are what they
// say and the same from the same seed, its placements are exact or refused,
// and a short run through the golden model of every path passes its checks.
// (Labelled golden: it reruns at the narrow width and under the sanitizers.)

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "common/error.h"
#include "driver/job.h"
#include "golden/formats.h"
#include "stress/stress.h"

namespace lancer::stress {
namespace {

bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(Stress, CasesAreTheSameFromTheSameSeed) {
  for (const std::string& name : caseNames()) {
    const StressCase a = makeCase(name, 120, 5), b = makeCase(name, 120, 5), c = makeCase(name, 120, 6);
    ASSERT_EQ(a.rays.size(), b.rays.size()) << name;
    ASSERT_EQ(a.scene.size(), b.scene.size()) << name;
    EXPECT_GE(a.rays.size(), 120u) << name;
    bool differs = a.rays.size() != c.rays.size();
    for (size_t i = 0; i < a.rays.size(); ++i) {
      EXPECT_TRUE(sameBits(a.rays[i].origin, b.rays[i].origin) && sameBits(a.rays[i].dir, b.rays[i].dir)) << name << i;
      if (i < c.rays.size()) differs |= !sameBits(a.rays[i].dir, c.rays[i].dir);
    }
    for (size_t t = 0; t < a.scene.size(); ++t) EXPECT_TRUE(sameBits(a.scene.triangles[t].v0, b.scene.triangles[t].v0));
    EXPECT_TRUE(differs) << name << ": another seed should draw other rays";
  }
}

TEST(Stress, CasesHoldWhatTheyPromise) {
  const StressCase closed = makeCase("closed-mesh", 200, 1);
  EXPECT_EQ(closed.mustHit, closed.rays.size());
  EXPECT_EQ(closed.scene.size(), 1280u);  // an icosahedron split three times

  const StressCase planes = makeCase("axis-planes", 300, 1);
  EXPECT_EQ(planes.accel.gridResolution, 16);
  size_t axisParallel = 0, signedZero = 0;
  for (const Ray& r : planes.rays) {
    const int zeros = (r.dir.x == 0) + (r.dir.y == 0) + (r.dir.z == 0);
    axisParallel += zeros == 2;
    signedZero += std::signbit(r.dir.x) && r.dir.x == 0;
  }
  EXPECT_GT(axisParallel, 100u);
  EXPECT_GT(signedZero, 10u);

  // The closed box: its faces are the scene's bounds, every ray enters it from outside.
  const StressCase box = makeCase("closed-box", 200, 1);
  EXPECT_EQ(box.mustHit, box.rays.size());
  EXPECT_EQ(box.scene.size(), 16u);  // 12 faces' triangles, two walls
  EXPECT_EQ(box.scene.bounds.lo, glm::vec3(-1.0f));
  EXPECT_EQ(box.scene.bounds.hi, glm::vec3(1.0f));
  for (const Ray& r : box.rays) {
    EXPECT_TRUE(glm::any(glm::lessThan(r.origin, glm::vec3(-1.0f))) ||
                glm::any(glm::greaterThan(r.origin, glm::vec3(1.0f))));
  }

  const StressCase tiny = makeCase("tiny-components", 300, 1);
  bool subnormal = false;
  for (const Ray& r : tiny.rays) {
    for (int a = 0; a < 3; ++a) subnormal |= std::fpclassify(r.dir[a]) == FP_SUBNORMAL;
  }
  EXPECT_TRUE(subnormal);
  EXPECT_THROW(makeCase("teapot", 10, 1), InputError);
}

TEST(Stress, PowerOfTwoScalesAreExact) {
  const StressCase base = makeCase("degenerate", 50, 1);
  const StressCase small = place(base, {Variant::Kind::Scale, -60});
  for (size_t t = 0; t < base.scene.size(); ++t) {
    EXPECT_EQ(small.scene.triangles[t].v1.x, std::ldexp(base.scene.triangles[t].v1.x, -60));
  }
  for (size_t i = 0; i < base.rays.size(); ++i) {
    EXPECT_EQ(small.rays[i].origin.z, std::ldexp(base.rays[i].origin.z, -60));
    EXPECT_TRUE(sameBits(small.rays[i].dir, base.rays[i].dir));
  }
  EXPECT_TRUE((Variant{Variant::Kind::Scale, 40}.latticeExact()));
  EXPECT_FALSE((Variant{Variant::Kind::Translate, 10}.latticeExact()));
}

TEST(Stress, PlacementsBeyondFloatRangeAndNaNRaysAreRefusedByName) {
  const StressCase base = makeCase("closed-mesh", 20, 1);
  try {
    place(base, {Variant::Kind::Scale, -140});
    FAIL() << "2^-140 leaves the icosphere's coordinates subnormal";
  } catch (const InputError& e) {
    EXPECT_NE(std::strstr(e.what(), "stress case closed-mesh, scale 2^-140: triangle 0 vertex"), nullptr) << e.what();
  }
  try {
    place(base, {Variant::Kind::Translate, 1e39});
    FAIL() << "a translation of 1e39 overflows float";
  } catch (const InputError& e) {
    EXPECT_NE(std::strstr(e.what(), "beyond float range"), nullptr) << e.what();
  }
  StressCase broken = makeCase("grazing", 20, 1);
  broken.rays[3].dir.y = std::nanf("");
  try {
    place(broken, {Variant::Kind::Base, 0});
    FAIL() << "a NaN ray must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::strstr(e.what(), "stress case grazing, base: ray 3: NaN"), nullptr) << e.what();
  }
  EXPECT_THROW(makeVariants({200}, {}, {}), InputError);
  EXPECT_THROW(makeVariants({}, {-1}, {}), InputError);
  EXPECT_THROW(makeVariants({}, {}, {std::nan("")}), InputError);
}

TEST(Stress, ThinScenesAndFarPlacementsAreWarnedOf) {
  const StressCase base = makeCase("grazing", 20, 1);
  const auto fitOf = [](const StressCase& c) { return latticeFit(c.scene, Quantizer(c.scene.bounds)); };
  EXPECT_TRUE(fitOf(base).warning.empty());
  const LatticeFit thin = fitOf(place(base, {Variant::Kind::Stretch, 10000}));
  EXPECT_LT(thin.shortestExtentUnits, 256);
  EXPECT_NE(thin.warning.find("shortest extent"), std::string::npos);
  const LatticeFit far = fitOf(place(base, {Variant::Kind::Translate, 1000}));
  if (fx::kPosBits >= 14) {  // float32's 24 bits, 10 of them spent on the offset
    EXPECT_GT(far.floatSpacingUnits, 0.5);
    EXPECT_NE(far.warning.find("float32"), std::string::npos);
  }
}

// The short form, on the golden model of every path: no answer beyond the
// lattice's bound, no crack where the lattice holds the shape, power-of-two
// scales identical bit for bit.
TEST(Stress, ShortRunPassesOnTheGoldenModels) {
  StressOptions options;
  options.models = {"golden"};
  options.rays = 120;
  options.scales = {-60, 60};
  options.translations = {1000};
  options.stretches = {10000};
  const StressResult r = runStress(options);
  EXPECT_EQ(r.failures(), 0u);
  EXPECT_EQ(r.placements.size(), caseNames().size() * 5);  // base, two scales, a translation, a stretch
  EXPECT_EQ(r.rows.size(), r.placements.size() * hardwarePaths().size());
  for (const StressRow& row : r.rows) {
    SCOPED_TRACE(row.caseName + ", " + row.variant + ", " + row.unit);
    EXPECT_EQ(row.mismatches, 0u);
    EXPECT_EQ(row.verdicts[0] + row.verdicts[1] + row.verdicts[2] + row.verdicts[3], row.rays);
    EXPECT_EQ(row.verdicts[3], 0u) << row.firstBeyondDetails;
    // No leak anywhere: a must-hit ray the hardware misses is one whose own
    // lattice ray passes outside its lattice mesh (only where the placement
    // distorts the scene's angles, never where it keeps the lattice exact).
    EXPECT_EQ(row.cracks, 0u);
    if (row.latticeExact) {
      EXPECT_EQ(row.baseDiffers, 0u);
      EXPECT_EQ(row.latticeMisses, 0u);
    }
  }
  const nlohmann::json j = r.toJson();
  EXPECT_EQ(j["pos_bits"], fx::kPosBits);
  EXPECT_EQ(j["rows"].size(), r.rows.size());
  EXPECT_NE(placementTable(r).find("scale 2^-60"), std::string::npos);
  // Another width's report comes back through JSON: the same tables and verdict.
  const StressResult back = StressResult::fromJson(j);
  EXPECT_EQ(placementTable(back), placementTable(r));
  EXPECT_EQ(modelTable(back), modelTable(r));
  EXPECT_EQ(back.toJson(), j);
}

TEST(Stress, UnknownUnitsAndModelsAreRefused) {
  StressOptions options;
  options.units = {"kdtree"};
  EXPECT_THROW(runStress(options), InputError);
  options.units = {"grid"};
  options.models = {"verilog"};
  EXPECT_THROW(runStress(options), InputError);
}

}  // namespace
}  // namespace lancer::stress
