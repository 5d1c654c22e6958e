#pragma once

#include <optional>

#include "golden/records.h"

namespace lancer::fx {

// Bit-accurate model of the intersection pipeline rt_isect: the watertight test
// of Woop, Benthin & Wald done in exact integer arithmetic. It defines the truth
// the SystemC model and the RTL are compared with. No rounding happens anywhere:
//
//  1. dominant axis kz of the direction (ties to the lower axis), kx, ky follow;
//  2. vertices relative to the origin, a = v0 - o, b = v1 - o, c = v2 - o;
//  3. shear scaled by d[kz] instead of divided by it (Woop divides):
//       ax = d[kz]*a[kx] - d[kx]*a[kz],  ay = d[kz]*a[ky] - d[ky]*a[kz];
//     shared vertices give bit-identical sheared values;
//  4. edge functions U = cx*by - cy*bx, V = ax*cy - ay*cx, W = bx*ay - by*ax,
//     each d[kz]^2 times Woop's, so their signs are Woop's. A shared edge gives
//     the exact negation in the neighbour, so no ray leaks through it;
//  5. inside unless the signs of U, V, W disagree; det = U + V + W, zero for a ray
//     in the triangle's plane or a degenerate triangle (a miss);
//  6. T = U*a[kz] + V*b[kz] + W*c[kz]; t = T / (d[kz] * det), a hit iff t > 0;
//  7. signs normalized so every output is non-negative; a miss outputs zeros;
//  8. a hit beyond the ray's segment end (t_num * 2^F > t_max * det) is a miss.
IsectResult intersect(const QRay& ray, const QTriangle& tri);

// The segment end as a pseudo hit (hit = 0; t_num = t_max, det = 2^F, so
// t_num / det is the end's displacement, as a hit's): what a traversal unit's
// exit test compares with before the ray has a hit.
IsectResult segmentEndBound(const QRay& ray);
// What ends a traversal walk after a region: the closest hit so far, else the
// segment end of a bounded ray, else nothing (the walk runs to the lattice's edge).
std::optional<IsectResult> walkBound(const QRay& ray, const std::optional<IsectResult>& closest);

// Dominant axis of an integer direction, the same rule as the float reference.
int dominantAxis(const std::array<int64_t, 3>& dir);

// Ordering of two hits of the same ray: smaller t by cross-multiplication
// (t_num_a * det_b < t_num_b * det_a, exact in 256 bits), ties to the lower prim id.
bool closerResult(const IsectResult& a, const IsectResult& b);

// The hit's t and barycentrics as doubles, in units of the quantized direction.
double tOf(const IsectResult& res, const QRay& ray);
double uOf(const IsectResult& res);
double vOf(const IsectResult& res);

}  // namespace lancer::fx
