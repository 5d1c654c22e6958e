#pragma once

// What a traversal unit's index list names (issue #40, docs/quadrics.md,
// "In the traversal units"): a triangle of the triangle table or a quadric of
// the quadric table. The entry's top bit is its kind, the rest its place in
// that table, so one list, one run per cell or leaf, holds both; a list is
// ascending, triangles first. Each record carries its scene primitive id.

#include <cstdint>
#include <span>
#include <vector>

#include "golden/isect.h"
#include "golden/lattice.h"
#include "golden/quadric.h"
#include "golden/trace.h"

namespace lancer::fx {

inline constexpr uint32_t triangleEntry(uint32_t place) { return place; }
inline constexpr uint32_t quadricEntry(uint32_t place) { return place | kQuadricEntryBit; }
inline constexpr bool isQuadricEntry(uint32_t entry) { return (entry & kQuadricEntryBit) != 0; }
inline constexpr uint32_t entryPlace(uint32_t entry) { return entry & ~kQuadricEntryBit; }
// The entry a primitive read names: its place and its table (a port's
// address and its kind bit, tri_req_quadric_o).
inline constexpr uint32_t primitiveEntry(uint32_t place, bool quadric) {
  return quadric ? quadricEntry(place) : triangleEntry(place);
}

// The primitive tables of an image, by place.
struct PrimitiveTables {
  std::span<const QTriangle> triangles;
  std::span<const QQuadric> quadrics;

  // The ray against the entry's primitive (the pipeline its kind goes to).
  IsectResult test(const QRay& ray, uint32_t entry) const {
    return isQuadricEntry(entry) ? intersectQuadric(ray, quadrics[entryPlace(entry)])
                                 : intersect(ray, triangles[entryPlace(entry)]);
  }
  // A lattice box holding the entry's primitive.
  LatticeBox bounds(uint32_t entry) const {
    return isQuadricEntry(entry) ? quadrics[entryPlace(entry)].bounds : latticeBounds(triangles[entryPlace(entry)]);
  }
  size_t size() const { return triangles.size() + quadrics.size(); }
  // Every entry, ascending: the triangles', then the quadrics'.
  std::vector<uint32_t> entries() const {
    std::vector<uint32_t> all;
    all.reserve(size());
    for (uint32_t i = 0; i < triangles.size(); ++i) all.push_back(triangleEntry(i));
    for (uint32_t i = 0; i < quadrics.size(); ++i) all.push_back(quadricEntry(i));
    return all;
  }
};

// One test of a walk: the entry's primitive against the ray, counted by kind,
// the closest hit kept (closerResult).
inline void testEntry(TraversalTrace& trace, const QRay& ray, const PrimitiveTables& primitives, uint32_t entry) {
  const IsectResult r = primitives.test(ray, entry);
  ++trace.tests;
  if (isQuadricEntry(entry)) ++trace.quadricTests;
  if (r.hit && (!trace.hit || closerResult(r, *trace.hit))) trace.hit = r;
}

// An image's tables (any unit's image: triangles and quadrics by place).
template <class Image>
PrimitiveTables tablesOf(const Image& image) {
  return {image.triangles, image.quadrics};
}

// The primitive tables renumbered by first listing in the index list (a
// layout's locality: a leaf's primitives near its neighbours'), each kind in
// its own table; every entry of `indices` rewritten to the new places.
// Primitives never listed are dropped.
inline void renumberPrimitivesByListing(std::vector<uint32_t>& indices, std::vector<QTriangle>& triangles,
                                        std::vector<QQuadric>& quadrics) {
  constexpr uint32_t kUnplaced = ~uint32_t(0);
  std::vector<uint32_t> triangleAt(triangles.size(), kUnplaced), quadricAt(quadrics.size(), kUnplaced);
  std::vector<QTriangle> newTriangles;
  std::vector<QQuadric> newQuadrics;
  newTriangles.reserve(triangles.size());
  newQuadrics.reserve(quadrics.size());
  for (uint32_t& entry : indices) {
    const uint32_t place = entryPlace(entry);
    const bool quadric = isQuadricEntry(entry);
    uint32_t& at = quadric ? quadricAt[place] : triangleAt[place];
    if (at == kUnplaced) {
      if (quadric) {
        at = uint32_t(newQuadrics.size());
        newQuadrics.push_back(quadrics[place]);
      } else {
        at = uint32_t(newTriangles.size());
        newTriangles.push_back(triangles[place]);
      }
    }
    entry = primitiveEntry(at, quadric);
  }
  triangles = std::move(newTriangles);
  quadrics = std::move(newQuadrics);
}

}  // namespace lancer::fx
