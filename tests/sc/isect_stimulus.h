#pragma once

// Stimulus for the SystemC tests of rt_isect: random ray-triangle pairs biased
// towards hits, and the hard cases of the watertight test.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "driver/isect_device.h"

namespace lancer::sctest {

// n pairs from `seed`: about half are triangles placed around a point of the
// ray (mostly hits), the rest random triangles anywhere (mostly misses).
std::vector<IsectRequest> randomPairs(size_t n, uint64_t seed);

// The hard cases, every one a pair with a unique ray id:
//  - rays through the vertices and edge midpoints of a closed lattice mesh (a
//    box, every face a grid of triangles), each paired with every triangle;
//    `meshRayHits` lists, per such ray id, that it must hit the mesh;
//  - degenerate triangles (a point, a segment, two equal vertices) and needles;
//  - rays in the plane of their triangle;
//  - directions with 0 and +-1 components and ties of the dominant axis;
//  - extreme coordinates: origins and vertices at 0 and kPosMax, +-kDirMax.
struct HardCases {
  std::vector<IsectRequest> pairs;
  std::vector<uint32_t> meshRays;  // ray ids that must hit the closed mesh
};
HardCases hardCases();

// The stats of a run equal to the reference device's on the same stimulus
// (every cycle-accurate device draws it alike from the same options).
void expectSameStats(const StreamStats& got, const StreamStats& want, std::string_view who);

// A reproducer line for a request: both records as hex wire images.
std::string describe(const IsectRequest& request);
std::string describe(const fx::IsectResult& result);

}  // namespace lancer::sctest
