#pragma once

// The grid unit's descriptor (golden/unit.h lists what a descriptor provides).

#include "golden/grid.h"
#include "golden/unit.h"

namespace lancer::fx {

// ---- grid_cfg_t: rt_grid's cfg_res_i, the resolution of a run -------------------
inline constexpr FieldSpec kGridCfgFields[] = {
    {"res", kGridResolutionBits, 3, false, "cells per axis, [0]=x"},
};

// Its configuration port, cfg_res_i, carries the resolution.
struct GridUnit : UnitBase<UnitKind::Grid, GridImage, GridCell, kGridCellFields, kGridCfgFields, kGridRecords,
                           kGridFormatParams, kGridLatencies> {
  static constexpr UnitNames kNames = unitNames<"grid">(
      {"cells", "cell", "cell table", "cfg_res_i", "voxel_steps", "voxel steps", "cell_reads", "cell table reads"});
  static constexpr size_t kGroup = 1;  // a node read returns one cell
  static constexpr int kSetupLatency = kGridSetupLatency;

  static const std::vector<Node>& nodes(const Image& image) { return image.cells; }
  static std::array<u128, 2> nodeValues(const Node& cell) { return {cell.first, cell.count}; }
  // The resolution; 1 x 1 x 1 (the reset value) for an empty Image.
  static std::array<u128, 3> configValues(const Image& image) {
    return {u128(image.res[0]), u128(image.res[1]), u128(image.res[2])};
  }

  // --grid-res R gives R cells on every axis; 0 chooses by the triangle count.
  static std::vector<BuildOption> buildOptions() {
    return {{"--grid-res", &AccelOptions::gridResolution,
             fmt::format("Grid cells per axis, 1..{} (default: from the triangle count)", kGridResMax), false,
             {"grid_resolution_x", "grid_resolution_y", "grid_resolution_z"}, true, kGridResMax}};
  }
  static Image build(std::vector<QTriangle> triangles, const AccelOptions& options, std::vector<QQuadric> quadrics = {}) {
    const int r = options.gridResolution;
    const GridRes res = r ? GridRes{r, r, r} : chooseGridResolution(PrimitiveTables{triangles, quadrics});
    return buildGridImage(std::move(triangles), res, std::move(quadrics));
  }

  static void checkImage(const Image& image, std::span<const QRay>) {
    for (int a = 0; a < 3; ++a) {
      if (image.res[a] < 1 || image.res[a] > kGridResMax) {
        throw InputError(
            fmt::format("grid resolution {} on axis {} is out of range 1..{}", image.res[a], a, kGridResMax));
      }
    }
  }

  static TraversalTrace traverse(const Image& image, const QRay& ray) { return traverseGrid(image, ray); }

  // One cell read per cell entered.
  struct NodeReads {
    explicit NodeReads(const Image&) {}
    uint64_t operator()(const TraversalTrace& trace) const { return trace.visits.size(); }
  };

  static std::vector<ImageCounter> imageCounters(const Image& image) {
    return {{"grid_resolution_x", "grid cells x", double(image.res[0])},
            {"grid_resolution_y", "grid cells y", double(image.res[1])},
            {"grid_resolution_z", "grid cells z", double(image.res[2])}};
  }
};

}  // namespace lancer::fx
