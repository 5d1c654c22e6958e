#pragma once

// What the hard cases of every traversal unit (grid_cases.h, octree_cases.h)
// are made of: a case record, quantized scenes and random lattice stimulus,
// the adverse run conditions for a cycle model, and one-line descriptions for
// mismatch reports.

#include <cstdint>
#include <random>
#include <string>
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

// A random lattice ray (direction normalized as the quantizer does), and random
// triangles (ids 0..count-1) with vertices within `spread` lattice units of a
// random centre in [lo, hi]^3, clamped to the lattice.
fx::QRay randomLatticeRay(std::mt19937_64& rng, uint32_t id);
std::vector<fx::QTriangle> randomLatticeTriangles(std::mt19937_64& rng, int count, int64_t lo, int64_t hi,
                                                  int64_t spread);

// Adverse conditions for a cycle model: memory latency 7 with 0..13 jitter,
// 30 % output stalls, 20 % input bubbles.
TraversalRunOptions roughTraversalOptions(uint64_t seed, int raysInFlight = 0);

// One-line descriptions for mismatch reports: the ray, and a trace with its
// first `shown` visits (`element`: "cells", "nodes").
std::string describeLatticeRay(const fx::QRay& ray);
std::string describeTraversalTrace(const fx::TraversalTrace& trace, const char* element, size_t shown);

}  // namespace lancer::test
