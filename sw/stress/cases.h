#pragma once

// The generated hard cases of `lancer stress` (docs/stability.md, "The
// stability suite"): scenes and rays in scene space, each built around one way
// a fixed-point or a float tracer can go wrong, the same from the same seed on
// every machine and compiler.
//
//   closed-mesh        a closed icosphere; rays aimed exactly (on the lattice) at
//                      its shared vertices and edge points, and float rays aimed
//                      at vertices and edge midpoints: every one must hit
//   closed-box         a closed box whose faces lie on the scene's bounds, with
//                      two walls across it (rooms): rays from outside entering
//                      through its faces, edges, corners and wall seams: every
//                      one must hit
//   axis-planes        axis-parallel rays with +0 / -0 components, and rays lying
//                      in the cell and node boundary planes of a 16^3 grid and a
//                      depth-4 octree, along their edges and through their corners
//   grazing            rays nearly in a triangle's plane (1e-2 to 1e-7 rad), aimed
//                      inside it and at its edges
//   degenerate         zero-area (collinear, repeated vertex), needle and sliver
//                      triangles among ordinary ones, rays aimed at them
//   coincident         duplicated triangles (same, rotated and reversed vertex
//                      order) and overlapping coplanar ones: the tie rule
//   origin-on-surface  rays starting on a triangle (at a vertex, inside), away
//                      from it, into it and along it
//   obj-text           a closed mesh read from OBJ text written with full-precision
//                      decimals (the nearest floats are not what is written);
//                      a power-of-two placement reads the text scaled by 2^k, so
//                      its bit-identical answers prove the reader rounds correctly;
//                      rays from far off with directions of any length
//   tiny-components    directions with components of 1e-7 .. 1e-45 (subnormal),
//                      +0 and -0 beside 1

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ref/accel.h"
#include "common/ray.h"
#include "scene/scene.h"

namespace lancer::stress {

struct StressCase {
  std::string name;
  std::string description;  // one line, for the legend
  Scene scene;
  std::vector<Ray> rays;
  // The first `mustHit` rays cross a closed surface transversally: a watertight
  // tracer hits every one, and a miss is a crack.
  size_t mustHit = 0;
  AccelOptions accel;       // the structures the rays are built against (e.g. a 16^3 grid)
  // A scene read from text: the scene as the text scaled by 2^k reads (the
  // reader's rounding is then under test, not float scaling). Empty: scaling
  // multiplies the floats.
  std::function<Scene(int exponent)> readScaled;
  uint64_t latticeRejected = 0;  // lattice-exact rays the quantizer did not reproduce (dropped)
};

const std::vector<std::string>& caseNames();

// The case `name` with about `rays` rays. Throws InputError for an unknown name.
StressCase makeCase(const std::string& name, size_t rays, uint64_t seed);

}  // namespace lancer::stress
