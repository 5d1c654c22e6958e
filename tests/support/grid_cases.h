#pragma once

// The hard cases of the grid unit (docs/grid-unit.md) as reusable stimulus:
// each a memory image and the quantized rays to walk through it, shared by the
// test programs of every model of the unit (the Verilated RTL in
// tests/rtl/grid/, the SystemC models in tests/sc/), which compare each model
// against fx::traverseGrid bit for bit.
//
//   axis-parallel     axis-parallel float rays with +0/-0 components, through
//                     lancer::Quantizer (bunny, 16^3)
//   planes ...        a 16^3 grid whose boundaries lie on lattice points: rays in
//                     the planes between voxels, along voxel edges, through voxel
//                     corners (exact ties on every axis), from the grid faces and
//                     corners, with a direction component of +-1
//   1x1x1, 256^3      one cell and the finest grid
//   empty cells       mostly empty cells, triangles spanning many cells (64x48x40)
//   crowded cell      thousands of triangles in one cell (4^3)
//   bunny random      random lattice rays over the bunny at 1x1x1, 3x7x5 and 32^3
//
// Every ray has a non-zero direction (the quantizer's rule: the dominant
// component is +-DIR_MAX) and ids 0..n-1 within its case. The bunny comes from
// LANCER_DATA_DIR/scenes/bunny.obj (scripts/deps).

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "driver/traversal_device.h"
#include "golden/grid.h"
#include "scene/scene.h"
#include "support/traversal_cases.h"

namespace lancer::test {

using GridCase = TraversalCase<fx::GridImage>;

// All the cases above, in that order (names unique).
std::vector<GridCase> gridHardCases();

// The bunny, loaded once.
const Scene& bunnyScene();

// A random lattice ray (direction normalized as the quantizer does) and random
// triangles with vertices within `spread` lattice units of a random centre.
inline fx::QRay randomGridRay(std::mt19937_64& rng, uint32_t id) { return randomLatticeRay(rng, id); }
inline std::vector<fx::QTriangle> randomGridTriangles(std::mt19937_64& rng, int count, int64_t spread) {
  return randomLatticeTriangles(rng, count, 0, fx::kPosMax, spread);
}

// rt_grid's CellQueue as the models are built (LANCER_GRID_CELL_QUEUE): a ray
// reads at most CellQueue - 1 cells past the one where it stops, so a model's
// cell reads lie in [golden, golden + (CellQueue - 1) * rays].
#ifndef LANCER_GRID_CELL_QUEUE
#error "LANCER_GRID_CELL_QUEUE must come from the build (rt_grid_vlt and lancer_systemc define it)"
#endif
inline constexpr uint64_t kGridCellQueue = LANCER_GRID_CELL_QUEUE;

}  // namespace lancer::test
