#pragma once

// Crack rays: rays aimed, in the hardware's own lattice, exactly at the shared
// edges and vertices of a mesh, crossing the surface there. A watertight test
// must hit every one of them (the point lies on a closed part of the surface);
// a hardware miss is a crack. The rays depend on the width of the build they are
// made in, because they are exact only on that build's lattice.
//
// Construction (docs/accuracy.md, "Cracks"): a direction d with components in
// {-1, 0, 1} quantizes exactly (its dominant component becomes +-kDirMax and the
// others +-kDirMax or 0), so a ray from a lattice origin o = p - m d passes
// exactly through p. For a vertex p is the vertex; for an edge (a, b) p is its
// midpoint (a + b) / 2, and m is half an odd integer where a + b is odd (d is
// +-1 on exactly those axes), so o stays on the lattice. d must cross both
// triangles of an edge (every triangle of a vertex's fan) from the same side,
// not in their planes. Each ray is checked through the driver's own quantizer:
// one that does not come out at exactly o and kDirMax d (float32 cannot hold
// every lattice point of a 24-bit lattice) is dropped and counted.

#include <cstdint>
#include <vector>

#include "driver/quantize.h"
#include "common/ray.h"
#include "scene/scene.h"

namespace lancer {

struct CrackRays {
  std::vector<Ray> rays;       // edge rays first, then vertex rays
  uint64_t edgeRays = 0;
  uint64_t vertexRays = 0;
  uint64_t sharedEdges = 0;    // lattice edges shared by exactly two non-degenerate triangles
  uint64_t closedVertices = 0; // lattice vertices every edge of which is shared
  uint64_t rejected = 0;       // candidates the quantizer did not reproduce exactly
};

// Up to `count` rays, about half at edges and half at vertices, chosen by `seed`.
CrackRays makeCrackRays(const Scene& scene, const Quantizer& quantizer, size_t count, uint64_t seed);

}  // namespace lancer
