#pragma once

// Stimulus for the tests of rt_quadric (the RTL, its cycle model): random
// sphere and cone pairs and the hard cases of docs/quadrics.md, deterministic
// in their seed and valid at any LANCER_POS_BITS / LANCER_DIR_BITS.

#include <cstdint>
#include <string>
#include <vector>

#include "driver/isect_device.h"

namespace lancer::rtltest {

// Random pairs: spheres and cones (a quarter cylinders, a quarter pointed) of
// every size on the lattice, half the rays aimed near the surface, a fifth with
// a segment end.
std::vector<QuadricRequest> randomQuadricPairs(size_t count, uint64_t seed);

// The hard cases, each a named group: tangent rays and one unit further;
// rays from inside, from the surface outwards and inwards; rays along a
// cylinder's axis (on it, inside, in the surface, outside); rays grazing a
// cone's rims in the end planes and one unit beyond; rays through the open
// end; pointed cones at the apex; radius 1 at a lattice corner and quadrics as
// wide as the lattice touching the scene box; the extreme origins and
// directions; segment ends just short of and at the surface.
struct QuadricCaseGroup {
  std::string name;
  std::vector<QuadricRequest> pairs;
};
std::vector<QuadricCaseGroup> quadricHardCases();

}  // namespace lancer::rtltest
