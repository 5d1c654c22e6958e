#pragma once

// What the hard cases of every traversal unit (grid_cases.h, octree_cases.h)
// are made of: a case record, quantized scenes and random lattice stimulus,
// the adverse run conditions for a cycle model, and one-line descriptions for
// mismatch reports.

#include <array>
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <random>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "driver/traversal_device.h"
#include "golden/records.h"
#include "golden/trace.h"
#include "scene/scene.h"

namespace lancer::test {

// One hard case of a unit: its memory image and the rays to walk through it.
template <class Image>
struct TraversalCase {
  std::string name;
  Image image;
  std::vector<fx::QRay> rays;
};

// One way to build a unit's image of a scene (a leaf size, a depth, a
// resolution), with how many of a test's rays it takes (a coarse build tests
// many triangles a ray) and the seed of its run's stimulus.
template <class Image>
struct BuildVariant {
  std::string name;
  Image image;
  size_t rays = 0;
  uint64_t seed = 0;
};

// A unit's hard cases (`Build`: bvhHardCases, octreeHardCases, ...) built once
// for the test program, and found by name: a value-parameterized test runs
// over caseNames<Build>() and looks its case up with caseNamed<Build>(name).
template <auto Build>
const auto& casesOnce() {
  static const auto cases = Build();
  return cases;
}

template <auto Build>
std::vector<std::string> caseNames() {
  std::vector<std::string> names;
  for (const auto& c : casesOnce<Build>()) names.push_back(c.name);
  return names;
}

template <auto Build>
const auto& caseNamed(const std::string& name) {
  for (const auto& c : casesOnce<Build>()) {
    if (c.name == name) return c;
  }
  throw std::logic_error("no hard case named " + name);
}

// Quantized triangles of a scene (lancer::Quantizer over its bounds, id = index)
// and its camera rays (frameScene, width x height) through the same quantizer;
// rays that miss the lattice cube are dropped, ids stay the pixel index.
struct QuantizedScene {
  std::vector<fx::QTriangle> triangles;
  std::vector<fx::QRay> rays;
};
QuantizedScene quantizedCamera(const Scene& scene, int width, int height);

// The quantizer's direction rule: the dominant component is exactly +-DIR_MAX.
fx::QRay normalizedDirection(fx::QRay ray);

// ---- What the hard cases are built from ----------------------------------------
using LatticePoint = std::array<int64_t, 3>;

// Triangles of a scene through lancer::Quantizer over its bounds (id = index),
// and the built-in Cornell box so, built once.
std::vector<fx::QTriangle> quantizeScene(const Scene& scene);
const std::vector<fx::QTriangle>& quantizedCornell();

// A uniformly random lattice point.
LatticePoint randomLatticePoint(std::mt19937_64& rng);

// From `org` towards `target`, scaled so the dominant component is +-kDirMax
// (rounded elsewhere: the ray passes near the target, not exactly through it).
fx::QRay aimedRay(const LatticePoint& org, const LatticePoint& target);

// The eight sign combinations of `dir` from `org` (a component of 0 stays 0:
// fewer distinct rays).
void addOctantRays(std::vector<fx::QRay>& rays, const LatticePoint& org, const LatticePoint& dir);

// Numbers the rays 0..n-1; a logic_error names the unit's case and the ray
// unless every ray starts on the lattice with a non-zero direction in range.
void numberCaseRays(std::string_view unit, const std::string& name, std::vector<fx::QRay>& rays);

template <class Image>
TraversalCase<Image> makeTraversalCase(std::string_view unit, std::string name, Image image,
                                       std::vector<fx::QRay> rays) {
  numberCaseRays(unit, name, rays);
  return {std::move(name), std::move(image), std::move(rays)};
}

// A random lattice ray (direction normalized as the quantizer does), and random
// triangles (ids 0..count-1) with vertices within `spread` lattice units of a
// random centre in [lo, hi]^3, clamped to the lattice.
fx::QRay randomLatticeRay(std::mt19937_64& rng, uint32_t id);
// `count` random lattice rays with ids 0..count-1, from a generator seeded with `seed`.
std::vector<fx::QRay> randomLatticeRays(uint64_t seed, uint32_t count);
std::vector<fx::QTriangle> randomLatticeTriangles(std::mt19937_64& rng, int count, int64_t lo, int64_t hi,
                                                  int64_t spread);

// A triangle's centroid, each coordinate rounded towards zero.
LatticePoint centroid(const fx::QTriangle& t);
// `count` random lattice rays (randomLatticeRay, id 0).
void addRandomRays(std::vector<fx::QRay>& rays, std::mt19937_64& rng, int count);
// `count` rays, each from a random lattice point aimed at (near) the centroid
// of a random triangle of `tris` (drawn first); none when `tris` is empty.
void addAimedRays(std::vector<fx::QRay>& rays, const std::vector<fx::QTriangle>& tris, std::mt19937_64& rng,
                  int count);
// `random` random rays, then `aimed` aimed rays at `tris`.
std::vector<fx::QRay> randomAndAimedRays(std::mt19937_64& rng, const std::vector<fx::QTriangle>& tris, int random,
                                         int aimed);

// A unit's hard cases from its table of case factories, in the table's order.
template <class Case>
std::vector<Case> makeCases(std::initializer_list<Case (*)()> factories) {
  std::vector<Case> cases;
  for (Case (*make)() : factories) cases.push_back(make());
  return cases;
}

// ---- Segment ends and any-hit (shadow rays) ------------------------------------
// A hit's displacement along the dominant axis in segment-end codes
// (formats.h): floor(2^F * t_num / det), and whether that is exact.
struct SegmentCode {
  uint64_t floor = 0;
  bool exact = false;
};
SegmentCode segmentCodeOf(const fx::IsectResult& hit);

// The closest hit of `ray` over `triangles` by brute force (fx::intersect, so
// within the ray's segment; fx::closerResult order).
std::optional<fx::IsectResult> bruteForceHit(std::span<const fx::QTriangle> triangles, const fx::QRay& ray);

// Rays with segment ends and the any-hit flag, from the first `maxRays` of
// `rays` over `triangles`: per ray with a hit, segments ending at the hit
// (floor and floor + 1 of its code: the hit counts exactly when the code is
// exact, and always with floor + 1), one code short of it (the hit is beyond),
// any-hit unbounded and any-hit ending at the hit; per ray, a segment ending a
// quarter of the way to the lattice's edge (a light inside the lattice) and an
// any-hit ray with no end (a light outside it). Ids 0..n-1.
std::vector<fx::QRay> segmentVariants(std::span<const fx::QTriangle> triangles, std::span<const fx::QRay> rays,
                                      size_t maxRays);

// A wall and an occluder for exact segment ends: two triangles in the plane
// z = zWall (ids 0, 1), a small occluder halfway between it and the origins
// (id 2); rays whose dominant axis is z from z = zOrigin, so every wall hit's
// displacement is exactly zWall - zOrigin: segments ending exactly at the wall
// (the hit counts), one code short (it does not), between the occluder and the
// wall (a light behind an occluder), before the occluder (nothing), any-hit
// and closest-hit alike, along +z and -z and obliquely. `zWall` on a cell or
// node boundary of the caller's structure puts the end on it.
QuantizedScene segmentScene(int64_t zWall, int64_t zOrigin);

// Adverse conditions for a cycle model: memory latency 7 with 0..13 jitter,
// 30 % output stalls, 20 % input bubbles.
TraversalRunOptions roughTraversalOptions(uint64_t seed, int raysInFlight = 0);

// One-line descriptions for mismatch reports: the ray, and a trace with its
// first `shown` visits (`element`: "cells", "nodes").
std::string describeLatticeRay(const fx::QRay& ray);
std::string describeTraversalTrace(const fx::TraversalTrace& trace, const char* element, size_t shown);

// The treelet schedule's stress run (the models' treelet tests): `units`
// units on the hierarchy, a queue memory of `queueKib`, the stream's bubbles
// and stalls, batches of 4 rays.
TraversalRunOptions treeletStressOptions(int units, int queueKib);

}  // namespace lancer::test
