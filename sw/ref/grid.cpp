#include "ref/grid.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "common/error.h"
#include "ref/primitive.h"

namespace lancer {

float binningEpsilon(const Aabb& b) {
  if (b.empty()) return 0.0f;
  // Rounding in the traversal and in the triangle test is a few dozen ulps of the
  // largest magnitude involved: the coordinates (up to M) and the distance along
  // the ray (up to a few extents E for origins near the scene). 2^-18 M is 32 ulps
  // of M; 2^-16 E is 128 ulps of E. The floor keeps a degenerate (point) scene's
  // box from having zero size.
  const glm::vec3 extent = b.diagonal();
  const float maxExtent = std::max({extent.x, extent.y, extent.z});
  const glm::vec3 mag = glm::max(glm::abs(b.lo), glm::abs(b.hi));
  const float maxMagnitude = std::max({mag.x, mag.y, mag.z});
  const float eps = std::ldexp(maxExtent, -16) + std::ldexp(maxMagnitude, -18);
  return std::max(eps, 1e-30f);
}

BinningBox binningBox(const Scene& scene, std::string_view structure) {
  if (scene.primitiveCount() > std::numeric_limits<uint32_t>::max()) {
    throw InputError(fmt::format("{}: more than 2^32 - 1 primitives", structure));
  }
  Aabb sceneBounds;
  for (const Triangle& t : scene.triangles) sceneBounds.extend(t.bounds());
  for (const Quadric& q : scene.quadrics) sceneBounds.extend(q.bounds());
  const float eps = binningEpsilon(sceneBounds);
  return BinningBox{Aabb{sceneBounds.lo - eps, sceneBounds.hi + eps}, eps};
}

namespace {

// Voxel counts for an explicit AccelOptions::gridResolution: `longest` voxels on
// the longest axis, the other axes in proportion (so voxels are near-cubic).
glm::ivec3 explicitResolution(const glm::vec3& extent, int longest) {
  const float maxExtent = std::max({extent.x, extent.y, extent.z});
  glm::ivec3 res;
  for (int a = 0; a < 3; ++a) {
    const double n = std::round(double(longest) * extent[a] / maxExtent);
    res[a] = static_cast<int>(std::clamp(n, 1.0, double(longest)));
  }
  return res;
}

// The classic heuristic (Cleary and Wyvill 1988; pbrt-v1's GridAccel has the same
// form with a larger lambda): about lambda * N near-cubic voxels, per-axis counts
// proportional to the box's extent, each clamped to [1, kMaxHeuristicAxis].
glm::ivec3 heuristicResolution(const glm::vec3& extent, size_t triangles) {
  const double maxExtent = std::max({extent.x, extent.y, extent.z});
  // Step 1: floor each extent at one voxel of the finest allowed grid, so a flat
  // scene has a non-zero volume and still gets about lambda * N voxels.
  glm::dvec3 e;
  for (int a = 0; a < 3; ++a) {
    e[a] = std::max(double(extent[a]), maxExtent / UniformGrid::kMaxHeuristicAxis);
  }
  // Step 2: the side s of a cubic voxel such that volume / s^3 = lambda * N.
  const double cells = UniformGrid::kCellsPerTriangle * double(std::max<size_t>(triangles, 1));
  const double side = std::cbrt(e.x * e.y * e.z / cells);
  // Step 3: per-axis counts, rounded and clamped.
  glm::ivec3 res;
  for (int a = 0; a < 3; ++a) {
    res[a] = static_cast<int>(
        std::clamp(std::round(extent[a] / side), 1.0, double(UniformGrid::kMaxHeuristicAxis)));
  }
  return res;
}

}  // namespace

UniformGrid::UniformGrid(const Scene& scene, const AccelOptions& options) : scene_(scene) {
  if (options.gridResolution < 0 || options.gridResolution > kMaxResolution) {
    throw InputError(fmt::format(
        "grid resolution {} is out of range (expected 1..{} voxels along the longest axis, "
        "or 0 for the heuristic)",
        options.gridResolution, kMaxResolution));
  }
  const size_t primitives = scene.primitiveCount();
  if (primitives == 0) {
    res_ = glm::ivec3(1);
    return;  // no voxels are stored; every ray misses
  }

  // Step 1: the gridded box, grown so that no triangle touches its faces.
  const auto [box, eps] = binningBox(scene, "grid");
  bounds_ = box;
  const glm::vec3 extent = bounds_.diagonal();
  res_ = options.gridResolution > 0 ? explicitResolution(extent, options.gridResolution)
                                    : heuristicResolution(extent, primitives);
  cellSize_ = extent / glm::vec3(res_);
  invCellSize_ = glm::vec3(res_) / extent;

  // Step 2: the voxel range of each primitive's grown bounding box. Binning by
  // the box rather than by an exact primitive-voxel overlap lists some
  // triangles in voxels they miss, and a quadric in every voxel its box
  // overlaps (conservative); that costs tests, never correctness.
  std::vector<std::array<glm::ivec3, 2>> ranges(primitives);
  for (size_t i = 0; i < primitives; ++i) {
    const Aabb tb = primitiveBounds(scene, uint32_t(i));
    for (int a = 0; a < 3; ++a) {
      const auto index = [&](float x) {
        const float c = std::floor((x - bounds_.lo[a]) * invCellSize_[a]);
        return static_cast<int>(std::clamp(c, 0.0f, float(res_[a] - 1)));
      };
      ranges[i][0][a] = index(tb.lo[a] - eps);
      ranges[i][1][a] = index(tb.hi[a] + eps);
    }
  }
  const auto forEachCell = [&](size_t tri, auto&& visit) {
    const auto& [lo, hi] = ranges[tri];
    for (int z = lo.z; z <= hi.z; ++z) {
      for (int y = lo.y; y <= hi.y; ++y) {
        const uint64_t row = (uint64_t(z) * res_.y + y) * res_.x;
        for (int x = lo.x; x <= hi.x; ++x) visit(row + x);
      }
    }
  };

  // Step 3: mark non-empty voxels and rank them.
  const uint64_t cells = uint64_t(res_.x) * res_.y * res_.z;
  occupied_.assign((cells + 63) / 64, 0);
  for (size_t i = 0; i < primitives; ++i) {
    forEachCell(i, [&](uint64_t c) { occupied_[c >> 6] |= uint64_t(1) << (c & 63); });
  }
  wordRank_.resize(occupied_.size());
  uint64_t nonEmpty = 0;
  for (size_t w = 0; w < occupied_.size(); ++w) {
    wordRank_[w] = static_cast<uint32_t>(nonEmpty);
    nonEmpty += std::popcount(occupied_[w]);
  }

  // Step 4: count references per voxel, prefix-sum them into run starts, then fill
  // the runs in primitive order (so each run is ascending).
  cellStart_.assign(nonEmpty + 1, 0);
  for (size_t i = 0; i < primitives; ++i) {
    forEachCell(i, [&](uint64_t c) { ++cellStart_[cellSlot(c) + 1]; });
  }
  uint64_t total = 0;
  for (size_t s = 1; s < cellStart_.size(); ++s) {
    total += cellStart_[s];
    if (total > std::numeric_limits<uint32_t>::max()) {
      throw InputError(
          fmt::format("grid of {}x{}x{} voxels needs more than 2^32 triangle "
                      "references; choose a smaller grid resolution",
                      res_.x, res_.y, res_.z));
    }
    cellStart_[s] = static_cast<uint32_t>(total);
  }
  triIndices_.resize(total);
  std::vector<uint32_t> cursor(cellStart_.begin(), cellStart_.end() - 1);
  for (size_t i = 0; i < primitives; ++i) {
    forEachCell(i,
                [&](uint64_t c) { triIndices_[cursor[cellSlot(c)]++] = static_cast<uint32_t>(i); });
  }
}

int64_t UniformGrid::cellSlot(uint64_t c) const {
  const uint64_t word = occupied_[c >> 6];
  const uint64_t bit = uint64_t(1) << (c & 63);
  if (!(word & bit)) return -1;
  return int64_t(wordRank_[c >> 6]) + std::popcount(word & (bit - 1));
}

// Why the traversal has no gaps: the voxels are visited in order of the t at
// which the ray enters them, and each voxel's entry t is the previous voxel's exit
// t, the same float (tNext of the axis just stepped), so the visited intervals
// chain from the clipped ray's start to its end. Where rounding puts a boundary
// crossing slightly off, the ray is within ulps of both voxels, and binning by
// boxes grown by binningEpsilon() lists every triangle near the boundary in both.
template <bool kAnyHit, bool kQuadrics>
std::optional<Hit> UniformGrid::traverse(const Ray& ray, TraversalStats* stats) const {
  if (triIndices_.empty()) return std::nullopt;
  const glm::vec3& o = ray.origin;
  const glm::vec3& d = ray.dir;
  // Not a ray: nothing is hit (see the class comment).
  if (!allFinite(o) || !allFinite(d) || std::isnan(ray.tMax)) return std::nullopt;
  if (d.x == 0.0f && d.y == 0.0f && d.z == 0.0f) return std::nullopt;

  // Step 1: clip the ray to the grid box slab by slab. A zero component (+0 or -0)
  // never crosses its slab: the ray is inside it for every t or for none, so it
  // constrains nothing, and no 0 * inf or inf - inf is ever formed.
  float tStart = 0.0f;
  float tEnd = ray.tMax;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0f) {
      if (o[a] < bounds_.lo[a] || o[a] > bounds_.hi[a]) return std::nullopt;
      continue;
    }
    // Division rather than a reciprocal: 1/d overflows for tiny d and (x - o) * inf
    // is NaN when x == o; x / d is a signed zero or infinity at worst.
    float t0 = (bounds_.lo[a] - o[a]) / d[a];
    float t1 = (bounds_.hi[a] - o[a]) / d[a];
    if (t0 > t1) std::swap(t0, t1);
    tStart = std::max(tStart, t0);
    tEnd = std::min(tEnd, t1);
  }
  // The negated test also rejects a NaN tMax; an infinite start (the ray reaches
  // the box only beyond the largest float) can hold no finite hit.
  if (!(tStart <= tEnd) || tStart == kInfinity) return std::nullopt;

  // Step 2: the voxel holding the entry point, and per axis the step and the t of
  // the next boundary crossing (+inf on an axis the ray never moves along).
  glm::ivec3 cell;
  glm::ivec3 step;
  glm::vec3 tNext;
  const auto boundaryT = [&](int a, int k) {
    return (bounds_.lo[a] + float(k) * cellSize_[a] - o[a]) / d[a];
  };
  for (int a = 0; a < 3; ++a) {
    const float p = d[a] == 0.0f ? o[a] : o[a] + tStart * d[a];
    const float c = std::floor((p - bounds_.lo[a]) * invCellSize_[a]);
    cell[a] = static_cast<int>(std::clamp(c, 0.0f, float(res_[a] - 1)));
    if (d[a] > 0.0f) {
      step[a] = 1;
      tNext[a] = boundaryT(a, cell[a] + 1);
    } else if (d[a] < 0.0f) {
      step[a] = -1;
      tNext[a] = boundaryT(a, cell[a]);
    } else {
      step[a] = 0;
      tNext[a] = kInfinity;
    }
  }

  // Step 3: walk the voxels.
  const WatertightRay wray(ray);
  std::optional<Hit> best;
  TriangleMailbox mailbox;
  for (;;) {
    if (stats) ++stats->nodesVisited;
    const float tExit = std::min({tNext.x, tNext.y, tNext.z});
    const uint64_t c = (uint64_t(cell.z) * res_.y + cell.y) * res_.x + cell.x;
    if (const int64_t slot = cellSlot(c); slot >= 0) {
      for (uint32_t k = cellStart_[slot]; k < cellStart_[slot + 1]; ++k) {
        const uint32_t prim = triIndices_[k];
        if (mailbox.testedBefore(prim)) continue;  // same ray, same primitive: same answer
        if (auto hit = intersectCounted<kQuadrics>(scene_, wray, ray, prim, stats)) {
          if constexpr (kAnyHit) return hit;
          keepCloser(best, *hit);
        }
      }
    }
    // Step 4: stop once the best hit lies within this voxel's t interval: any
    // closer (or tied) hit would lie within this voxel too, so it was tested here.
    // A hit beyond tExit may still lose to a triangle in a later voxel.
    if (best && best->t <= tExit) break;
    if (tExit >= tEnd) break;
    // Step 5: cross the nearest boundary (ties to the lowest axis: through an edge
    // the ray visits one of the side voxels, which touch the ray only on the edge).
    const int axis =
        tNext.x <= tNext.y ? (tNext.x <= tNext.z ? 0 : 2) : (tNext.y <= tNext.z ? 1 : 2);
    cell[axis] += step[axis];
    if (cell[axis] < 0 || cell[axis] >= res_[axis]) break;
    // Each crossing is computed afresh from the plane's position, not by adding
    // tDelta, so its error does not grow with the number of steps.
    tNext[axis] = boundaryT(axis, step[axis] > 0 ? cell[axis] + 1 : cell[axis]);
  }
  return best;
}

std::optional<Hit> UniformGrid::intersect(const Ray& ray, TraversalStats* stats) const {
  return scene_.quadrics.empty() ? traverse<false, false>(ray, stats) : traverse<false, true>(ray, stats);
}

bool UniformGrid::intersectP(const Ray& ray) const {
  return (scene_.quadrics.empty() ? traverse<true, false>(ray, nullptr) : traverse<true, true>(ray, nullptr))
      .has_value();
}

}  // namespace lancer
