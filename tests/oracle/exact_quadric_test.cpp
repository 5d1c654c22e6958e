// The exact arbiter on quadrics (sw/oracle/exact.h; docs/oracle.md, "Quadrics
// in the exact arbiter and the float reference"): square-root-free signs, rays
// whose truth is known by construction (tangent, along a cylinder's axis, in a
// rim's plane, through an open end), the closest hit of a mixed scene with its
// tie rule, the verdicts on the float reference, and Embree's user geometry
// judged against it on random mixed scenes.

#include <gtest/gtest.h>

#include <cstdlib>

#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include <fmt/format.h>

#include "oracle/embree_accel.h"
#include "oracle/exact.h"
#include "ref/brute_force.h"
#include "ref/quadric.h"
#include "scene/scene.h"
#include "support/mixed_scenes.h"

namespace lancer {
namespace {

Ray rayOf(glm::vec3 origin, glm::vec3 dir, float tMax = kInfinity) { return {origin, dir, tMax}; }

Scene sceneOf(std::vector<Triangle> triangles, std::vector<Quadric> quadrics) {
  return test::mixedScene(std::move(triangles), std::move(quadrics));
}

// The ray in hex and both answers: a reproducer.
std::string reproducer(const Ray& ray, const std::optional<ExactHit>& truth, const std::optional<Hit>& answer) {
  return fmt::format("ray ({:a}, {:a}, {:a}) + t ({:a}, {:a}, {:a}), tMax {:a}; truth {} at {}; answer {} at {}",
                     ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x, ray.dir.y, ray.dir.z, ray.tMax,
                     truth ? int(truth->prim) : -1, truth ? truth->t : 0.0, answer ? int(answer->prim) : -1,
                     answer ? answer->t : 0.0f);
}

// The float reference over a mixed scene: every triangle and quadric.
std::optional<Hit> referenceHit(const Scene& scene, const Ray& ray) { return BruteForce(scene).intersect(ray); }

TEST(ExactQuadric, QuadraticIrrationalsCompareWithoutASquareRoot) {
  const auto t = [](long num, long coef, long radicand, long den, long shift = 0) {
    return ExactT(mpz_class(num), mpz_class(coef), mpz_class(radicand), mpz_class(den), shift);
  };
  EXPECT_EQ(compare(t(0, 1, 8, 1), t(0, 2, 2, 1)), 0);            // sqrt 8 = 2 sqrt 2
  EXPECT_EQ(compare(t(0, 1, 2, 1), ExactT(3, 2, 0)), -1);          // sqrt 2 < 3/2
  EXPECT_EQ(compare(t(3, -1, 2, 1), t(0, 1, 3, 1)), -1);           // 3 - sqrt 2 < sqrt 3
  EXPECT_EQ(compare(t(1, 1, 2, 1), t(0, 1, 3, 1, 1)), -1);         // 1 + sqrt 2 (2.414) < 2 sqrt 3 (3.46)
  EXPECT_EQ(compare(t(3, 2, 2, 1), t(1, 1, 2, 1, 0)), 1);
  EXPECT_EQ(compare(t(3, 2, 2, 1), t(0, 1, 17, 1) ), 1);           // 3 + 2 sqrt 2 (5.83) > sqrt 17 (4.12)
  EXPECT_EQ(compare(t(1, 1, 2, 1), t(-1, 1, 2, 1)), 1);
  EXPECT_EQ(t(-1, 1, 2, -3).sign(), -1);
  EXPECT_EQ(t(-2, 1, 4, 1).sign(), 0);
  // toDouble: within an ulp, also where the terms nearly cancel.
  EXPECT_NEAR(t(0, 1, 2, 1).toDouble(), std::sqrt(2.0), 4e-16);
  const ExactT close(mpz_class(1) << 40, mpz_class(-1), (mpz_class(1) << 80) - 1, mpz_class(1), 0);  // 2^40 - sqrt(2^80 - 1)
  EXPECT_NEAR(close.toDouble(), 0x1p-41, 0x1p-41 * 1e-15);
}

TEST(ExactQuadric, TangentOnDyadicInputsIsAHitOnTheBoundaryAndOneUlpAwayAMiss) {
  const Scene scene = sceneOf({}, {Quadric::sphere({0, 0, 0}, 1), Quadric::cone({10, 0, 0}, 2, {10, 0, 4}, 2)});
  const ExactOracle oracle(scene);
  // x = 1: tangent to the unit sphere at (1, 0, 0).
  auto hit = oracle.intersect(rayOf({1, 0, -4}, {0, 0, 1}));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->prim, 0u);
  EXPECT_EQ(hit->t, 4.0);
  EXPECT_TRUE(hit->onBoundary);
  EXPECT_TRUE(hit->entering);
  EXPECT_FALSE(oracle.intersect(rayOf({std::nextafter(1.0f, 2.0f), 0, -4}, {0, 0, 1})));
  hit = oracle.intersect(rayOf({std::nextafter(1.0f, 0.0f), 0, -4}, {0, 0, 1}));
  ASSERT_TRUE(hit);
  EXPECT_FALSE(hit->onBoundary);
  EXPECT_LT(hit->t, 4.0);
  // A slanted tangent: the line x + z = 2 sqrt(2)... is not dyadic; x = 1
  // along (0, 1, 1) is, tangent at (1, 0, 0) with t = 1.
  hit = oracle.intersect(rayOf({1, -1, -1}, {0, 1, 1}));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 1.0);
  EXPECT_TRUE(hit->onBoundary);
  // The cylinder of radius 2 about x = 10: tangent along y at x = 12, z = 2.
  hit = oracle.intersect(rayOf({12, -5, 2}, {0, 1, 0}));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->prim, 1u);
  EXPECT_EQ(hit->t, 5.0);
  EXPECT_TRUE(hit->onBoundary);
  EXPECT_FALSE(oracle.intersect(rayOf({std::nextafter(12.0f, 13.0f), -5, 2}, {0, 1, 0})));
  // The float reference takes the same tangents.
  EXPECT_TRUE(intersectQuadric(rayOf({12, -5, 2}, {0, 1, 0}), scene.quadrics[1], 1));
  EXPECT_FALSE(intersectQuadric(rayOf({std::nextafter(12.0f, 13.0f), -5, 2}, {0, 1, 0}), scene.quadrics[1], 1));
}

TEST(ExactQuadric, RaysAlongACylindersAxisNeverHitIt) {
  const Scene scene = sceneOf({}, {Quadric::cone({0, 0, 0}, 1, {0, 0, 4}, 1), Quadric::cone({0, 0, 0}, 3, {12, 12, 0}, 3)});
  const ExactOracle oracle(scene);
  for (const float x : {0.0f, 0.5f, 1.0f, 3.0f}) {
    const Ray ray = rayOf({x, 0, -1}, {0, 0, 1});
    EXPECT_FALSE(oracle.relation(ray, 0).hit) << x;
    EXPECT_TRUE(oracle.relation(ray, 0).parallel) << x;
  }
  // The oblique cylinder, along its axis (1, 1, 0): inside, in its wall, outside.
  for (const glm::vec3 o : {glm::vec3(-1, -1, 0), glm::vec3(-1, -1, 3), glm::vec3(-1, -1, 5)}) {
    EXPECT_FALSE(oracle.relation(rayOf(o, {1, 1, 0}), 1).hit);
    EXPECT_TRUE(oracle.relation(rayOf(o, {1, 1, 0}), 1).parallel);
  }
}

TEST(ExactQuadric, RimsInTheirEndPlanesAndTheOpenEnd) {
  // Radius 2 at z = 0, 1 at z = 2.
  const Scene scene = sceneOf({}, {Quadric::cone({0, 0, 0}, 2, {0, 0, 2}, 1)});
  const ExactOracle oracle(scene);
  // In the end planes: the rims, exactly.
  auto hit = oracle.intersect(rayOf({-5, 0, 0}, {1, 0, 0}));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 3.0);
  EXPECT_TRUE(hit->onBoundary);
  hit = oracle.intersect(rayOf({-5, 0, 2}, {1, 0, 0}));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 4.0);
  EXPECT_TRUE(hit->onBoundary);
  EXPECT_FALSE(oracle.intersect(rayOf({-5, 0, std::nextafter(0.0f, -1.0f)}, {1, 0, 0})));
  EXPECT_FALSE(oracle.intersect(rayOf({-5, 0, std::nextafter(2.0f, 3.0f)}, {1, 0, 0})));
  // Slanted through the base rim: its near root at the rim (t = 2, entering).
  hit = oracle.intersect(rayOf({-4, 0, -1}, {1, 0, 0.5f}));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 2.0);
  EXPECT_TRUE(hit->onBoundary);
  EXPECT_TRUE(hit->entering);
  // An ulp lower it passes below the rim, in through the open base, and hits
  // the inside wall at t = 5.2 (leaving).
  hit = oracle.intersect(rayOf({-4, 0, std::nextafter(-1.0f, -2.0f)}, {1, 0, 0.5f}));
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t, 5.2, 1e-6);
  EXPECT_FALSE(hit->entering);
  EXPECT_FALSE(hit->onBoundary);
  // A cylinder entered through its open base, hitting the inside wall at t = 2.
  const Scene cylinder = sceneOf({}, {Quadric::cone({0, 0, 0}, 1, {0, 0, 4}, 1)});
  const ExactOracle inside(cylinder);
  hit = inside.intersect(rayOf({0, 0, -1}, {0.5f, 0, 1}));
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->t, 2.0);
  EXPECT_FALSE(hit->entering);
  EXPECT_FALSE(inside.intersect(rayOf({0, 0, -1}, {0.5f, 0, 1}, std::nextafter(2.0f, 0.0f))));
  EXPECT_TRUE(inside.intersect(rayOf({0, 0, -1}, {0.5f, 0, 1}, 2.0f)));
  EXPECT_FALSE(inside.intersect(rayOf({0, 0, -1}, {0.1f, 0, 1})));  // out through the far end
}

TEST(ExactQuadric, ClosestHitAmongASphereAConeAndATriangleWithExactTies) {
  // On the ray from the origin along z: a triangle in z = 3, a sphere whose
  // front is at z = 3, a cylinder along x whose front is at z = 3.5.
  const Triangle plane{{-10, -10, 3}, {10, -10, 3}, {0, 10, 3}};
  const Quadric sphere = Quadric::sphere({0, 0, 5}, 2);
  const Quadric cylinder = Quadric::cone({-5, 0, 4}, 0.5f, {5, 0, 4}, 0.5f);
  const Ray ray = rayOf({0, 0, 0}, {0, 0, 1});
  {
    const Scene scene = sceneOf({plane}, {sphere, cylinder});
    const ExactOracle oracle(scene);
    const auto hit = oracle.intersect(ray);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->prim, 0u);  // the triangle and the sphere tie exactly at t = 3: the lower id
    EXPECT_EQ(hit->t, 3.0);
    EXPECT_TRUE(*oracle.relation(ray, 1).t == *oracle.relation(ray, 0).t);
    EXPECT_EQ(oracle.hitsOnSegment(ray).size(), 3u);
    EXPECT_EQ(judge(oracle, ray, Hit{1, 3.0f}, hit).verdict, Verdict::Tie);
    EXPECT_EQ(judge(oracle, ray, Hit{2, 3.5f}, hit).verdict, Verdict::Wrong);
  }
  {
    // The sphere first, now the lower id of the tie.
    const Scene scene = sceneOf({}, {sphere, Quadric::cone({-5, 0, 4}, 1, {5, 0, 4}, 1)});
    const ExactOracle oracle(scene);
    const auto hit = oracle.intersect(ray);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->prim, 0u);
    EXPECT_EQ(hit->t, 3.0);
  }
  {
    // Sphere moved back: the cone at 3.5 is nearest.
    const Scene scene = sceneOf({}, {Quadric::sphere({0, 0, 6}, 2), cylinder});
    const ExactOracle oracle(scene);
    const auto hit = oracle.intersect(ray);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->prim, 1u);
    EXPECT_EQ(hit->t, 3.5);
  }
  {
    // Irrational roots tie exactly: two spheres the line x = 0.5 meets at
    // t = 10 - sqrt(0.75), the second listed first to see the lower id win.
    const Ray offset = rayOf({0.5f, 0, 0}, {0, 0, 1});
    const Scene scene = sceneOf({}, {Quadric::sphere({1, 0, 10}, 1), Quadric::sphere({0, 0, 10}, 1),
                                     Quadric::sphere({0, 0.25f, 10}, 1)});
    const ExactOracle oracle(scene);
    const auto hit = oracle.intersect(offset);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->prim, 0u);
    EXPECT_NEAR(hit->t, 10.0 - std::sqrt(0.75), 1e-14);
    EXPECT_TRUE(*oracle.relation(offset, 0).t == *oracle.relation(offset, 1).t);
    // The third, its center 0.25 off the line's plane, at 10 - sqrt(0.6875): farther.
    EXPECT_EQ(compare(*oracle.relation(offset, 2).t, *oracle.relation(offset, 1).t), 1);
  }
}

TEST(ExactQuadric, VerdictsOnTangentsOriginsAndRims) {
  const Scene scene = sceneOf({}, {Quadric::sphere({0, 0, 0}, 1)});
  const ExactOracle oracle(scene);
  // A miss by one ulp of the tangent: a tracer's hit there is rounding.
  const Ray outside = rayOf({std::nextafter(1.0f, 2.0f), 0, -4}, {0, 0, 1});
  EXPECT_EQ(judge(oracle, outside, Hit{0, 4.0f}, oracle.intersect(outside)).verdict, Verdict::Rounding);
  const Ray inside = rayOf({std::nextafter(1.0f, 0.0f), 0, -4}, {0, 0, 1});
  EXPECT_EQ(judge(oracle, inside, std::nullopt, oracle.intersect(inside)).verdict, Verdict::Rounding);
  // A miss through the middle, or a hit where the line passes far away, is wrong.
  const Ray middle = rayOf({0, 0, -4}, {0, 0, 1});
  EXPECT_EQ(judge(oracle, middle, std::nullopt, oracle.intersect(middle)).verdict, Verdict::Wrong);
  EXPECT_EQ(judge(oracle, middle, Hit{0, 3.0f}, oracle.intersect(middle)).verdict, Verdict::Correct);
  EXPECT_EQ(judge(oracle, middle, Hit{0, 5.0f}, oracle.intersect(middle)).verdict, Verdict::Wrong);
  const Ray away = rayOf({1.5f, 0, -4}, {0, 0, 1});
  EXPECT_EQ(judge(oracle, away, Hit{0, 4.0f}, oracle.intersect(away)).verdict, Verdict::Wrong);
  // From an origin on the surface, outwards: exactly no hit (t = 0); a
  // tracer's t of 1e-9 is rounding. Inwards: the far side, and the root at
  // the origin is rounding too.
  const Ray leaving = rayOf({1, 0, 0}, {1, 0, 0});
  EXPECT_FALSE(oracle.intersect(leaving));
  EXPECT_EQ(judge(oracle, leaving, Hit{0, 1e-9f}, std::nullopt).verdict, Verdict::Rounding);
  const Ray entering = rayOf({1, 0, 0}, {-1, 0, 0});
  EXPECT_EQ(oracle.intersect(entering)->t, 2.0);
  EXPECT_EQ(judge(oracle, entering, Hit{0, 1e-9f}, oracle.intersect(entering)).verdict, Verdict::Rounding);
  EXPECT_EQ(judge(oracle, entering, Hit{0, 1.0f}, oracle.intersect(entering)).verdict, Verdict::Wrong);
  // The rim: a ray an ulp below a cone's rim plane that a tracer rounds onto the rim.
  const Scene coneScene = sceneOf({}, {Quadric::cone({0, 0, 0}, 2, {0, 0, 2}, 1)});
  const ExactOracle cone(coneScene);
  const Ray below = rayOf({-4, 0, std::nextafter(-1.0f, -2.0f)}, {1, 0, 0.5f});
  EXPECT_EQ(judge(cone, below, Hit{0, 2.0f}, cone.intersect(below)).verdict, Verdict::Rounding);
  // Any-hit: a shadow ray ending at the sphere, and one clear of it.
  const Ray shadow = rayOf({0, 0, -4}, {0, 0, 1}, 3.0f);
  EXPECT_EQ(judgeAnyHit(oracle, shadow, Hit{0, 3.0f}).verdict, Verdict::Correct);
  EXPECT_EQ(judgeAnyHit(oracle, shadow, std::nullopt).verdict, Verdict::Rounding);  // t = tMax exactly
  const Ray clear = rayOf({0, 0, -4}, {0, 0, 1}, 2.0f);
  EXPECT_EQ(judgeAnyHit(oracle, clear, Hit{0, 3.0f}).verdict, Verdict::Wrong);
  // A tolerance hook of one's own: a lattice-sized edge excuses a miss by 0.01.
  const Ray near = rayOf({1.01f, 0, -4}, {0, 0, 1});
  EXPECT_EQ(judge(oracle, near, Hit{0, 4.0f}, oracle.intersect(near)).verdict, Verdict::Wrong);
  const QuadricToleranceOf coarse = [](const Quadric&) { return Tolerance{0.02, 0.02, 0.0}; };
  EXPECT_EQ(judge(oracle, near, Hit{0, 4.0f}, oracle.intersect(near), {}, coarse).verdict, Verdict::Rounding);
}

// Random mixed scenes (support/mixed_scenes.h): the float reference and
// Embree (its quadrics a user geometry) are judged against the exact truth:
// never wrong.
using test::RandomScenes;

// Three answers of the hardware on the SPD's scenes that the judge first put
// beyond the lattice's bound (docs/oracle.md): each within a move of the
// answered quadric's surface, found only by trying moves below the tolerance
// and shifts square to a cone's axis (the tree) and by measuring at the moved
// root nearest the answer (the rings).
TEST(ExactQuadric, MovesBelowTheToleranceAndTheMovedRootNearestTheAnswer) {
  const auto h = [](const char* s) { return float(std::strtod(s, nullptr)); };
  const auto within = [](double edge) {
    return QuadricToleranceOf([edge](const Quadric&) { return Tolerance{edge, edge, 0x1p-23}; });
  };
  {
    // The tree: a ray almost along a short branch's axis, 0.0011 outside its
    // wall. Moved out by 0.001 the wall is hit; by the whole tolerance, 0.0043,
    // the ray passes through both open ends.
    const Scene tree = sceneOf({}, {Quadric::cone({0.193114f, 0.292903f, 2.78861f}, 0.00273426f,
                                                  {0.215605f, 0.293961f, 2.78648f}, 0.00183195f),
                                    Quadric::cone({0.0533514f, 0.2903f, 2.77482f}, 0.00909107f,
                                                  {0.0897071f, 0.289571f, 2.83581f}, 0.00609102f)});
    const ExactOracle oracle(tree);
    const Ray ray = rayOf({4.5f, h("0x1.99999ap-2"), 2.0f}, {h("-0x1.f77d34p-1"), h("-0x1.9c6c6cp-6"), h("0x1.70462p-3")});
    const auto truth = oracle.intersect(ray);
    ASSERT_TRUE(truth && truth->prim == 1);
    const Hit answer{0, 4.37410116f, 0.0f, 0.0f};
    EXPECT_EQ(judge(oracle, ray, answer, truth, {}, within(0.00426)).verdict, Verdict::Rounding);
    EXPECT_EQ(judge(oracle, ray, answer, truth, {}, within(0.0005)).verdict, Verdict::Wrong)
        << "a move of 0.0005 does not reach the wall";
  }
  {
    // The rings: a cylinder ending in a sphere of its radius; the answer is
    // the cylinder's near root, just past its end plane, where the exact hit
    // on the cylinder is the inside wall behind.
    const Scene rings = sceneOf({}, {Quadric::cone({0.287693f, 12.1802f, 4.0f}, 0.07412f,
                                                   {-0.753191f, 12.5184f, 4.0f}, 0.07412f),
                                     Quadric::sphere({0.287693f, 12.1802f, 4.0f}, 0.07412f)});
    const ExactOracle oracle(rings);
    const Ray ray = rayOf({-1.0f, -2.61313009f, 0.5f}, {0.0832918212f, 0.969377935f, 0.231016949f});
    const auto truth = oracle.intersect(ray);
    ASSERT_TRUE(truth && truth->prim == 1);
    const Hit answer{0, 15.1885366f, 0.0f, 0.0f};
    EXPECT_EQ(judge(oracle, ray, answer, truth, {}, within(0.0016)).verdict, Verdict::Rounding);
  }
  {
    // The tree again: a shadow ray leaving a joint, almost along the next
    // branch (a cone 1.2 lattice units thick between two spheres) and 0.0012
    // outside it where it passes its far end. The branch's wall reaches the
    // ray only for a growth between 0.0012 and 0.0020 of the tolerance's
    // 0.0042, and a shift toward the ray decides it as well: blocked is
    // within the bound, not beyond a tolerance of 0.001.
    const Scene joint = sceneOf({}, {Quadric::cone({1.15543f, -0.189264f, 2.21941f}, 0.00183195f,
                                                   {1.15841f, -0.181437f, 2.22643f}, 0.00122741f),
                                     Quadric::sphere({1.15543f, -0.189264f, 2.21941f}, 0.00183195f),
                                     Quadric::sphere({1.15841f, -0.181437f, 2.22643f}, 0.00122741f)});
    const ExactOracle oracle(joint);
    const Ray ray = rayOf({h("0x1.284fcap+0"), h("-0x1.78975ap-3"), h("0x1.1c1b3ap+1")},
                          {h("0x1.707306p-3"), h("0x1.3a6012p-1"), h("0x1.897b34p-1")}, h("0x1.893b5ep+5"));
    ASSERT_TRUE(oracle.hitsOnSegment(ray).empty()) << "the segment is clear in exact arithmetic";
    const Hit blocked{0, h("0x1.a2566ep-8"), 0.0f, 0.0f};
    EXPECT_EQ(judgeAnyHit(oracle, ray, blocked, {}, within(0.00417)).verdict, Verdict::Rounding);
    EXPECT_EQ(judgeAnyHit(oracle, ray, blocked, {}, within(0.001)).verdict, Verdict::Wrong);
  }
}

TEST(ExactQuadric, FloatReferenceIsNeverWrongOnRandomMixedScenes) {
  RandomScenes random;
  int correct = 0, total = 0, quadricHits = 0, offJudged = 0, offWrong = 0;
  std::array<int, 4> verdicts{};
  for (int s = 0; s < 6; ++s) {
    const Scene scene = random.scene(6, 12);
    const ExactOracle oracle(scene);
    for (int k = 0; k < 500; ++k) {
      const Ray ray = random.ray(scene);
      const auto truth = oracle.intersect(ray);
      const auto answer = referenceHit(scene, ray);
      const Judgement j = judge(oracle, ray, answer, truth);
      EXPECT_NE(j.verdict, Verdict::Wrong)
          << j.reason << ", scene " << s << " ray " << k << ": " << reproducer(ray, truth, answer);
      correct += j.verdict == Verdict::Correct;
      ++verdicts[size_t(j.verdict)];
      quadricHits += truth && scene.isQuadric(truth->prim);
      ++total;
      // The judge is not lenient: a quadric's hit reported 1% too far is wrong
      // unless the ray grazes it.
      if (truth && scene.isQuadric(truth->prim) && !truth->onBoundary && truth->t > 1e-3 &&
          oracle.relation(ray, truth->prim).cosine > 0.1) {
        ++offJudged;
        offWrong += judge(oracle, ray, Hit{truth->prim, float(truth->t * 1.01)}, truth).verdict == Verdict::Wrong;
      }
      // Any-hit: blocked exactly when some primitive is hit on the segment.
      EXPECT_NE(judgeAnyHit(oracle, ray, answer).verdict, Verdict::Wrong) << "scene " << s << " ray " << k;
    }
  }
  std::printf("float reference on %d rays (%d quadric hits): %d correct, %d tie, %d rounding, %d wrong; "
              "t * 1.01 wrong on %d of %d\n",
              total, quadricHits, verdicts[0], verdicts[1], verdicts[2], verdicts[3], offWrong, offJudged);
  EXPECT_GT(quadricHits, total / 5);
  EXPECT_GT(correct, total * 99 / 100);
  EXPECT_GT(offWrong, offJudged * 95 / 100);
}

TEST(ExactQuadric, EmbreeAgreesWithTheExactArbiterOnRandomMixedScenes) {
  RandomScenes random;
  random.rng.seed(4041);
  int correct = 0, total = 0, quadricHits = 0;
  std::array<int, 4> verdicts{};
  for (int s = 0; s < 6; ++s) {
    const Scene scene = random.scene(s == 0 ? 0 : 8, 16);
    const ExactOracle oracle(scene);
    const EmbreeAccel embree(scene);
    for (int k = 0; k < 500; ++k) {
      const Ray ray = random.ray(scene);
      const auto truth = oracle.intersect(ray);
      const auto answer = embree.intersect(ray);
      const Judgement j = judge(oracle, ray, answer, truth);
      EXPECT_NE(j.verdict, Verdict::Wrong)
          << j.reason << ", scene " << s << " ray " << k << ": " << reproducer(ray, truth, answer);
      // Any-hit: Embree's occlusion callbacks, the blocker its closest hit.
      const bool blocked = embree.intersectP(ray);
      EXPECT_EQ(blocked, answer.has_value()) << "scene " << s << " ray " << k;
      EXPECT_NE(judgeAnyHit(oracle, ray, blocked ? answer : std::nullopt).verdict, Verdict::Wrong)
          << "scene " << s << " ray " << k;
      correct += j.verdict == Verdict::Correct || j.verdict == Verdict::Tie;
      ++verdicts[size_t(j.verdict)];
      quadricHits += answer && scene.isQuadric(answer->prim);
      ++total;
    }
  }
  std::printf("embree on %d rays (%d quadric hits): %d correct, %d tie, %d rounding, %d wrong\n", total, quadricHits,
              verdicts[0], verdicts[1], verdicts[2], verdicts[3]);
  EXPECT_GT(quadricHits, total / 5);
  EXPECT_GT(correct, total * 99 / 100);
}

}  // namespace
}  // namespace lancer
