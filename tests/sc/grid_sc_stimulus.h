#pragma once

// Stimulus for the SystemC tests of rt_grid: the bunny camera rays through the
// quantizer, random rays and triangles, and the hard cases of the RTL test
// (tests/rtl/grid/rt_grid_test.cpp), each as an image plus rays.

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "driver/traversal_device.h"
#include "golden/grid.h"

namespace lancer::sctest {

struct GridCase {
  std::string name;
  fx::GridImage image;
  std::vector<fx::QRay> rays;
};

struct QuantizedScene {
  std::vector<fx::QTriangle> triangles;
  std::vector<fx::QRay> rays;
};

// Camera rays of the bunny (width x height) through the Quantizer, as the driver makes them.
QuantizedScene bunnyCamera(int width, int height);

// The hard cases: axis-parallel rays with +0/-0 components, rays in planes
// between voxels, along voxel edges, through voxel corners, from grid faces
// and corners, tiny direction components, a 1x1x1 and a 256^3 grid, empty
// cells with large triangles, a crowded cell, random rays at several resolutions.
std::vector<GridCase> hardGridCases();

// Adverse conditions: memory jitter, output stalls, input bubbles.
TraversalRunOptions roughGridOptions(uint64_t seed, int raysInFlight = 0);

std::string describe(const fx::QRay& ray);
std::string describe(const fx::GridTrace& trace);

}  // namespace lancer::sctest
