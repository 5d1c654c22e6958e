#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "ref/accel.h"
#include "common/aabb.h"

namespace lancer {

// How far every primitive's bounding box is grown before it is binned into grid
// voxels or octree nodes, and how far the structure's box is grown around the
// scene. Traversal computes cell boundaries in float; growing the boxes by more
// than that rounding error means a triangle whose hit lies within rounding of a
// cell boundary is listed on both sides, so no hit is lost and early termination
// is never premature. See docs/reference-tracer.md for the error budget.
float binningEpsilon(const Aabb& sceneBounds);

// The box a structure (grid, octree) is built over: the bounds of the scene's
// primitives (triangles and quadrics' Quadric::bounds()), recomputed rather
// than read from scene.bounds (which a hand-made Scene may have left stale),
// grown by `eps` = binningEpsilon() of them, so that no primitive touches its
// faces. Throws InputError ("<structure>: more than 2^32 - 1 primitives") when
// the primitives outnumber the uint32_t ids.
struct BinningBox {
  Aabb bounds;
  float eps;
};
BinningBox binningBox(const Scene& scene, std::string_view structure);

// A tiny direct-mapped cache of the triangles one ray has already tested (shared
// by the grid and the octree, where a triangle is listed in several cells).
// Skipping a re-test is exact: the same ray and triangle give the same answer,
// which keepCloser() has already seen. Lives on the stack, no allocation.
class TriangleMailbox {
 public:
  TriangleMailbox() { ids_.fill(~uint32_t(0)); }
  bool testedBefore(uint32_t prim) {
    uint32_t& slot = ids_[prim % ids_.size()];
    if (slot == prim) return true;
    slot = prim;
    return false;
  }

 private:
  std::array<uint32_t, 16> ids_;
};

// A uniform grid over the scene bounds, traversed by the 3D-DDA of Amanatides
// and Woo (1987). Returns bit-identical hits to BruteForce. A native quadric is
// listed in every voxel its grown Quadric::bounds() overlaps (a triangle's
// box likewise); a scene without quadrics runs a triangle-only traversal.
//
// Storage: one bit per voxel says "non-empty"; a rank per 64-voxel word turns a
// non-empty voxel into an index into cellStart_, which delimits its run in one
// flat triangle-index array. That keeps a 1024-voxel-per-axis grid at about
// 1.5 bits per voxel plus the references, instead of 4 bytes per voxel.
//
// A ray with a non-finite origin or direction, a zero direction or a NaN tMax
// hits nothing (BruteForce's answer for those is not meaningful).
class UniformGrid final : public Accel {
 public:
  // Throws InputError unless options.gridResolution is 0 (heuristic) or 1..1024.
  UniformGrid(const Scene& scene, const AccelOptions& options);
  // The grid keeps a reference to the scene: a temporary would dangle.
  UniformGrid(Scene&&, const AccelOptions&) = delete;

  std::string_view name() const override { return "grid"; }
  std::optional<Hit> intersect(const Ray& ray, TraversalStats* stats = nullptr) const override;
  bool intersectP(const Ray& ray) const override;

  // Voxels along x, y and z.
  glm::ivec3 resolution() const { return res_; }
  // The gridded box: the scene bounds grown by binningEpsilon().
  const Aabb& bounds() const { return bounds_; }
  // Primitive references over all voxels (a primitive is listed once per voxel).
  size_t referenceCount() const { return triIndices_.size(); }

  static constexpr int kMaxResolution = 1024;       // for AccelOptions::gridResolution
  static constexpr int kMaxHeuristicAxis = 256;     // per-axis cap of the heuristic
  static constexpr float kCellsPerTriangle = 4.0f;  // lambda of the heuristic

 private:
  // Closest-hit (kAnyHit false) or any-hit (kAnyHit true) traversal; kQuadrics:
  // the scene has quadrics (each listed primitive is tested by its kind).
  template <bool kAnyHit, bool kQuadrics>
  std::optional<Hit> traverse(const Ray& ray, TraversalStats* stats) const;
  // Index into cellStart_ of a voxel's run, or -1 for an empty voxel.
  int64_t cellSlot(uint64_t cell) const;

  const Scene& scene_;
  Aabb bounds_;
  glm::ivec3 res_{0};
  glm::vec3 cellSize_{0.0f};
  glm::vec3 invCellSize_{0.0f};
  std::vector<uint64_t> occupied_;    // bit c of word c/64: voxel c is non-empty
  std::vector<uint32_t> wordRank_;    // non-empty voxels before word w
  std::vector<uint32_t> cellStart_;   // per non-empty voxel, plus one end marker
  std::vector<uint32_t> triIndices_;  // primitive ids, ascending within a voxel
};

}  // namespace lancer
