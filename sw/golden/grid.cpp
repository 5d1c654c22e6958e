#include "golden/grid.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "common/error.h"
#include "golden/isect.h"
#include "golden/lattice.h"
#include "golden/memory_image.h"
#include "golden/wide.h"

namespace lancer::fx {

GridRes chooseGridResolution(const PrimitiveTables& primitives) {
  std::array<int64_t, 3> lo{kPosMax, kPosMax, kPosMax}, hi{0, 0, 0};
  for (uint32_t entry : primitives.entries()) {
    const LatticeBox box = primitives.bounds(entry);
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], box.lo[a]);
      hi[a] = std::max(hi[a], box.hi[a]);
    }
  }
  std::array<double, 3> extent{};
  double volume = 1.0;
  for (int a = 0; a < 3; ++a) {
    extent[a] = double(std::max<int64_t>(hi[a] - lo[a], 1));
    volume *= extent[a];
  }
  const double k = std::cbrt(kCellsPerTriangle * double(std::max<size_t>(primitives.size(), 1)) / volume);
  GridRes res{};
  for (int a = 0; a < 3; ++a) res[a] = int(std::clamp<double>(std::round(extent[a] * k), 1.0, kGridResMax));
  return res;
}

GridImage buildGridImage(std::vector<QTriangle> triangles, const GridRes& res, std::vector<QQuadric> quadrics) {
  for (int a = 0; a < 3; ++a) {
    if (res[a] < 1 || res[a] > kGridResMax) {
      throw InputError(fmt::format("grid resolution {}x{}x{} is out of range: each axis must lie in 1..{}", res[0],
                                   res[1], res[2], kGridResMax));
    }
  }
  GridImage image;
  image.res = res;
  const uint64_t cellCount = uint64_t(res[0]) * uint64_t(res[1]) * uint64_t(res[2]);
  auto checkFits = [](const char* region, uint64_t entries) {
    checkRegionFits("grid", region, entries, "lower --grid-res");
  };
  checkFits("cell table", cellCount);
  checkFits("triangle table", triangles.size());
  checkFits("quadric table", quadrics.size());
  image.triangles = std::move(triangles);
  image.quadrics = std::move(quadrics);
  const PrimitiveTables primitives = tablesOf(image);
  const std::vector<uint32_t> entries = primitives.entries();

  // Cell range of a triangle on one axis, boundaries included: cell i spans the
  // scaled interval [i 2^P, (i+1) 2^P]; a box [lo, hi] touches it iff
  // i <= (hi R) >> P and i >= ceil(lo R / 2^P) - 1.
  auto range = [&](int64_t lo, int64_t hi, int r) {
    const int64_t scaledLo = lo * r, scaledHi = hi * r;
    const int64_t first = ((scaledLo + (int64_t(1) << kPosBits) - 1) >> kPosBits) - 1;
    const int64_t last = scaledHi >> kPosBits;
    return std::pair<int, int>{int(std::max<int64_t>(first, 0)), int(std::min<int64_t>(last, r - 1))};
  };
  // Two passes (count, then fill) so a 256^3 grid needs no per-cell containers.
  auto forEachCell = [&](uint32_t entry, auto&& visit) {
    std::array<std::pair<int, int>, 3> span{};
    const LatticeBox box = primitives.bounds(entry);
    for (int a = 0; a < 3; ++a) span[a] = range(box.lo[a], box.hi[a], res[a]);
    for (int z = span[2].first; z <= span[2].second; ++z)
      for (int y = span[1].first; y <= span[1].second; ++y)
        for (int x = span[0].first; x <= span[0].second; ++x) visit(image.cellId({x, y, z}));
  };
  image.cells.resize(cellCount);
  uint64_t references = 0;
  for (uint32_t entry : entries) {
    forEachCell(entry, [&](uint32_t cell) { ++image.cells[cell].count; });
  }
  for (GridCell& cell : image.cells) {
    cell.first = uint32_t(references);
    references += cell.count;
    checkFits("index list", references);
    cell.count = 0;
  }
  image.indices.resize(references);
  for (uint32_t entry : entries) {  // ascending entries within each cell
    forEachCell(entry, [&](uint32_t cell) {
      GridCell& c = image.cells[cell];
      image.indices[c.first + c.count++] = entry;
    });
  }
  return image;
}

GridDda GridDda::setup(const GridRes& res, const QRay& ray) {
  GridDda dda;
  dda.res = res;
  std::array<u128, 3> absD{};
  std::array<u128, 3> dist{};
  const u128 cellSpan = u128(1) << kPosBits;
  for (int a = 0; a < 3; ++a) {
    const int64_t scaled = ray.org[a] * res[a];  // X = o R
    dda.cell[a] = int(std::min<int64_t>(scaled >> kPosBits, res[a] - 1));
    dda.step[a] = ray.dir[a] > 0 ? 1 : (ray.dir[a] < 0 ? -1 : 0);
    absD[a] = u128(std::llabs(ray.dir[a]) * res[a]);
    // Distance (scaled units) to the boundary the ray crosses next on this axis.
    const int64_t lower = int64_t(dda.cell[a]) << kPosBits;
    dist[a] = dda.step[a] > 0 ? u128(lower + int64_t(cellSpan) - scaled) : u128(scaled - lower);
  }
  for (int a = 0; a < 3; ++a) {
    u128 pair = 1;
    for (int b = 0; b < 3; ++b) {
      if (b != a && dda.step[b] != 0) pair *= absD[b];
    }
    dda.acc[a] = dist[a] * pair;
    dda.inc[a] = cellSpan * pair;
    if (dda.step[a] != 0) dda.triple *= absD[a];
  }
  dda.dominant = u128(std::llabs(ray.dir[dominantAxis(ray.dir)]));
  return dda;
}

int GridDda::nextAxis() const {
  int best = -1;
  for (int a = 0; a < 3; ++a) {
    if (step[a] != 0 && (best < 0 || acc[a] < acc[best])) best = a;
  }
  return best;
}

bool GridDda::advance() {
  const int a = nextAxis();
  if (a < 0) return false;  // a zero direction (never quantized) stays in its first cell
  cell[a] += step[a];
  if (cell[a] < 0 || cell[a] >= res[a]) return false;
  acc[a] += inc[a];
  return true;
}

bool GridDda::holds(const IsectResult& hit) const {
  if (nextAxis() < 0) return true;
  const u128 exitAcc = acc[nextAxis()];
  return !(mul256(exitAcc * dominant, hit.det) < mul256(hit.tNum, triple));
}

GridTrace traverseGrid(const GridImage& image, const QRay& ray) {
  GridTrace trace;
  const PrimitiveTables primitives = tablesOf(image);
  GridDda dda = GridDda::setup(image.res, ray);
  for (;;) {
    const uint32_t id = dda.cellId();
    trace.visits.push_back(id);
    const GridCell& cell = image.cells[id];
    for (uint32_t k = 0; k < cell.count; ++k) testEntry(trace, ray, primitives, image.indices[cell.first + k]);
    if (ray.anyHit && trace.hit) break;  // any hit answers: no exit test
    if (const auto bound = walkBound(ray, trace.hit); bound && dda.holds(*bound)) break;
    if (!dda.advance()) break;
  }
  return trace;
}

}  // namespace lancer::fx
