#pragma once

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
//  7. signs normalized so every output is non-negative; a miss outputs zeros.
IsectResult intersect(const QRay& ray, const QTriangle& tri);

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
