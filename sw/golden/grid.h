#pragma once

// Bit-accurate model of the integer-DDA uniform-grid traversal unit (rt_grid):
// the memory image the driver builds for it, and the traversal that defines
// which voxels each ray visits and which hit it returns. docs/grid-unit.md has
// the derivation; every value here is an exact integer.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "golden/grid_formats.h"
#include "golden/primitives.h"
#include "golden/records.h"
#include "golden/trace.h"

namespace lancer::fx {

using GridRes = std::array<int, 3>;

// One entry of the cell table: a run of the index list.
struct GridCell {
  uint32_t first = 0;  // first entry in the index list
  uint32_t count = 0;  // triangles listed in the cell
  bool operator==(const GridCell&) const = default;
};

// The memory image the grid unit reads: three regions, each addressed from 0.
struct GridImage {
  GridRes res{1, 1, 1};
  std::vector<GridCell> cells;       // cell id = (z * Ry + y) * Rx + x
  std::vector<uint32_t> indices;     // primitive entries (golden/primitives.h); ascending within a cell
  std::vector<QTriangle> triangles;  // by place (a triangle's place is its id)
  std::vector<QQuadric> quadrics;    // by place

  uint32_t cellId(const std::array<int, 3>& c) const {
    return uint32_t((c[2] * res[1] + c[1]) * res[0] + c[0]);
  }
};

// Cells about kCellsPerTriangle per primitive, per axis proportional to the
// extent of the primitives' lattice boxes, each axis clamped to 1..kGridResMax.
inline constexpr double kCellsPerTriangle = 4.0;
GridRes chooseGridResolution(const PrimitiveTables& primitives);
inline GridRes chooseGridResolution(std::span<const QTriangle> triangles) {
  return chooseGridResolution(PrimitiveTables{triangles, {}});
}

// Bins every primitive into every cell its lattice box (a triangle's integer
// bounding box, a quadric's record bounds) touches, cell boundaries included
// (so a hit exactly on a boundary is listed on both sides). Throws InputError
// for a resolution outside 1..kGridResMax or an image that does not fit
// kMemAddrBits.
GridImage buildGridImage(std::vector<QTriangle> triangles, const GridRes& res, std::vector<QQuadric> quadrics = {});

// The DDA state of one ray: only additions and comparisons after setup().
struct GridDda {
  GridRes res{};
  std::array<int, 3> cell{};      // current cell
  std::array<int, 3> step{};      // +1, -1, or 0 for an axis the ray never crosses
  std::array<u128, 3> acc{};      // N_a: t of the next crossing times `triple`
  std::array<u128, 3> inc{};      // added to N_a per crossing on axis a
  u128 triple = 1;                // product of |D| over the axes that step
  u128 dominant = 1;              // |d[kz]| of the unscaled direction (the pipeline's t scale)

  // Per-ray setup: multiplications only.
  static GridDda setup(const GridRes& res, const QRay& ray);
  uint32_t cellId() const { return uint32_t((cell[2] * res[1] + cell[1]) * res[0] + cell[0]); }
  // The axis whose boundary comes first; exact ties go to the lowest axis,
  // which visits the cells around a crossed edge or corner one axis at a time
  // (never skipping a cell the ray touches).
  int nextAxis() const;
  // Moves to the next cell; false when the ray leaves the grid.
  bool advance();
  // True if `hit` (a pipeline result of this ray) lies within the current cell:
  // t_hit <= t_exit, exactly: t_num * triple <= N_min * |d[kz]| * det.
  bool holds(const IsectResult& hit) const;
};

using GridTrace = TraversalTrace;

// The reference behaviour of the unit for one ray: visit a cell, test its
// triangles, stop if the closest hit so far lies within the cell, else step.
GridTrace traverseGrid(const GridImage& image, const QRay& ray);

}  // namespace lancer::fx
