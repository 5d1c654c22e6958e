#pragma once

// Stimulus for the tests of rt_isect: random pairs and the hard cases, shared by
// the GoogleTest bench (rt_isect_test.cpp) and the Icarus vector writer
// (make_isect_vectors.cpp) so both simulators see the same corners. Every
// generator is deterministic in its seed and valid at any LANCER_POS_BITS /
// LANCER_DIR_BITS.

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "driver/isect_device.h"

namespace lancer::rtltest {

using Vec3 = std::array<int64_t, 3>;

// Stream options with random backpressure: the consumer stalls with `stall`,
// the producer idles with `idle`, both drawn from `seed`.
inline StreamOptions backpressure(double stall, double idle, uint64_t seed) {
  StreamOptions o;
  o.outputStallProbability = stall;
  o.inputIdleProbability = idle;
  o.seed = seed;
  return o;
}

// Random pairs: a mix of rays aimed at a point inside the triangle (mostly
// hits), unaimed rays (mostly misses), large and small triangles, quantized
// directions (dominant component +-kDirMax) and arbitrary direction codes.
std::vector<IsectRequest> randomPairs(size_t count, uint64_t seed);

// A closed octahedron on the lattice (8 triangles, 6 shared vertices, 12 shared
// edges, consistently oriented), centred in the cube.
std::vector<fx::QTriangle> octahedron();

// Rays aimed exactly at lattice points of the octahedron's vertices and edges
// (they pass through the point at t = 1), and rays from its centre in random
// directions. Each ray is paired with all 8 faces, in groups of 8 consecutive
// requests: a watertight test hits at least one face of every group.
std::vector<IsectRequest> watertightRays(size_t rays, uint64_t seed);
inline constexpr size_t kOctahedronFaces = 8;

// The same for random closed tetrahedra (vertices on a 4-unit sub-lattice, so
// edges have lattice points at 1/4, 1/2, 3/4 and the centroid is a lattice
// point): every ray with its tetrahedron's 4 faces, in groups of 4.
std::vector<IsectRequest> watertightTetraRays(size_t rays, uint64_t seed);
inline constexpr size_t kTetraFaces = 4;

// The corners, each a named group of pairs.
struct CaseGroup {
  std::string name;
  std::vector<IsectRequest> pairs;
};
// Degenerate (zero-area) and needle triangles; rays parallel to and in the
// triangle's plane; direction components 0 and +-1; ties of the dominant axis;
// ties between triangles (shared edges, coincident copies); the largest and
// smallest coordinates (0, kPosMax) and directions (+-kDirMax, and the unused
// code -kDirMax-1), including the combinations that maximize every
// intermediate of the pipeline; segment ends at, past and short of a hit, with
// and without the any-hit flag.
std::vector<CaseGroup> hardCases(uint64_t seed);

// All of the above in one stream (what the Icarus bench replays).
std::vector<IsectRequest> allHardCases(uint64_t seed);

}  // namespace lancer::rtltest
