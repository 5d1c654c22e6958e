#pragma once

// Bit-accurate model of the quadric tests (issue #40, docs/quadrics.md): a ray
// against a sphere or an NFF cone on the position lattice, in integers, as the
// quadric pipeline will compute it. The result is an isect_res_t like a
// triangle's, on the same scale (t_num / det is the hit's displacement along
// the ray's dominant axis, in lattice units), so closerResult orders spheres,
// cones and triangles alike.

#include <algorithm>
#include <array>
#include <cstdint>

#include "golden/formats.h"
#include "golden/records.h"
#include "golden/wide.h"

namespace lancer::fx {

// A sphere on the lattice: its center (0 .. kPosMax per axis) and radius
// (1 .. kPosMax lattice units).
struct QSphere {
  uint32_t id = 0;
  std::array<int64_t, 3> center{};
  int64_t radius = 1;
  bool operator==(const QSphere&) const = default;
};

// The widths of the sphere test, from P = kPosBits and D = kDirBits:
//   m = o - c                        P + 1 bits signed
//   A = d.d                          2D - 1 bits (d_i < 2^(D-1)), > 0
//   B = m.d                          P + D + 1 bits signed
//   C = m.m - r^2                    2P + 3 bits signed
//   disc = B^2 - A C                 2P + 2D + 4 bits signed
//   s = floor(sqrt(disc))            P + D + 2 bits
//   roots n = -B -+ s (over A)       P + D + 3 bits signed
inline constexpr int kSphereDiscBits = 2 * kPosBits + 2 * kDirBits + 4;
inline constexpr int kSphereRootBits = kPosBits + kDirBits + 2;
static_assert(kSphereDiscBits <= 127, "the discriminant is computed in 128-bit integers");

// floor(sqrt(v)) of a non-negative 128-bit integer: the digit-by-digit method
// the pipeline unrolls, one result bit a stage (kSphereRootBits stages).
u128 isqrt(u128 v);

// The ray against the sphere. The line meets it where |m + lambda d|^2 = r^2,
// lambda = (-B -+ sqrt(disc)) / A; with s = floor(sqrt(disc)) the pipeline
// takes the nearer root n = -B - s if it is > 0 (the ray enters the sphere),
// else the farther n = -B + s if it is > 0 (the ray starts inside and leaves
// it), else none; disc < 0 is a miss, disc = 0 the tangent (one root). The hit
// is t_num = n |d_dominant|, det = A (a displacement along the dominant axis,
// as a triangle's), within the segment as a triangle's is (t_num 2^F <=
// t_max det); u_num is 0 for the entering root and 1 for the leaving one,
// v_num 0. The error: the entering root is late by less than |d_dom| / A <=
// 1 / |d_dom| lattice units, the leaving one early by as little; whether the
// line meets the sphere is exact.
IsectResult intersectSphere(const QRay& ray, const QSphere& sphere);

// ---- The cone ----------------------------------------------------------------
// An NFF cone on the lattice: base center b and apex center a (0 .. kPosMax per
// axis, a != b), radii r0 at b and r1 at a (0 .. kPosMax lattice units, not
// both 0), open ends; a cylinder when r0 = r1. (NFF's negative radii, "inside
// visible", are the shader's business: the result says which side was hit.)
struct LatticeCone {
  std::array<int64_t, 3> base{}, apex{};
  int64_t baseRadius = 1, apexRadius = 1;
};

// K: the quadric part of a cone's record is rounded to |Q_ij| <= 2^K. The
// largest K whose per-ray arithmetic stays in 128-bit integers (the
// discriminant, 2P + 2D + 2K + 10 bits signed: all 128 at 16/16, K = 27) and
// whose result fits the triangles' record (t_num 3P + 2D + 3 bits, det
// 2(P + D) + 3 bits: docs/quadrics.md, "The cone").
inline constexpr int kConeQuadBits = std::min({59 - kPosBits - kDirBits, kPosBits + kDirBits - 4, 2 * kPosBits - 2});
// The widths of the cone test, from P, D and K (bounds on magnitudes):
//   q = 2o - (a + b)                 |q_i| < 2^(P+1)         P + 2 bits signed
//   A = d'Qd                         |A| < 2^(K+2D+2)       K + 2D + 3 bits signed
//   B = d'(Qq + g)                   |B| < 2^(P+D+K+4)      P + D + K + 5 bits signed
//   C = q'Qq + 2g'q + k              |C| < 2^(2P+K+6)       2P + K + 7 bits signed
//   disc = B^2 - A C                 |disc| < 2^(2P+2D+2K+9)
//   s = floor(sqrt(disc))            s < 2^(P+D+K+5)
//   big = -(B + sgn(B) s)            |big| < 2^(P+D+K+6)
//   roots big / 2A, C / 2big         denominators < 2^(P+D+K+7)
//   planes |(q.w) den + 2 num (d.w)| <= W den              < 2^(3P+D+K+11)
inline constexpr int kConeDiscBits = 2 * kPosBits + 2 * kDirBits + 2 * kConeQuadBits + 10;
inline constexpr int kConeRootBits = kPosBits + kDirBits + kConeQuadBits + 5;
static_assert(kConeQuadBits >= 8, "too few bits for the cone's quadric");
static_assert(kConeDiscBits <= 128, "the cone's discriminant is computed in 128-bit integers");
static_assert(3 * kPosBits + kDirBits + kConeQuadBits + 11 <= 127, "the cone's plane test is computed in 128-bit integers");
static_assert(2 * kPosBits + kConeQuadBits + 3 <= 64, "the record's constant is a 64-bit integer");
static_assert(6 * kPosBits + 6 <= 126, "the host computes the exact quadric in 128-bit integers");

// The cone's record, precomputed by the host (coneRecord): the exact quadric
// of the lattice cone, in the frame q = 2x - (a + b) (doubled, so that the
// axis' midpoint, where the rounding matters least, is an integer),
//   F(q) = W^2 |q|^2 - W (q.w)^2 - ((r0 + r1) W + (r1 - r0)(q.w))^2
//        = 4 W^2 (radial distance^2 - radius at the point's height^2),
// divided by 2^e and rounded to integers so that |Q_ij| <= 2^K: the record
// states exactly the quadric q'Qq + 2g'q + k = 0 the pipeline traces, within
// the bound of docs/quadrics.md of the scene's cone. Two planes cut it: the
// pipeline keeps points with |q.w| <= W (between the base and the apex).
struct QCone {
  uint32_t id = 0;
  std::array<int64_t, 3> axisSum{};  // a + b per axis: the frame's origin, P + 1 bits
  std::array<int64_t, 3> axis{};     // w = a - b, P + 1 bits signed
  int64_t axisLen2 = 0;              // W = w.w, 2P + 2 bits
  std::array<int64_t, 6> quad{};     // Q: xx, yy, zz, yz, xz, xy; |Q_ij| <= 2^K
  std::array<int64_t, 3> lin{};      // g: |g_i| <= 2^(P+K+1)
  int64_t constant = 0;              // k <= 0: |k| <= 2^(2P+K+2)
  int scaleExp = 0;                  // e (host only, for the error bound): exact F = 2^e times the record's, within rounding
  bool operator==(const QCone&) const = default;
  int64_t quadAt(int i, int j) const { return i == j ? quad[size_t(i)] : quad[size_t(6 - i - j)]; }
};

// The record of a lattice cone. Throws std::invalid_argument on what is no cone
// (both radii 0, base = apex) or lies off the lattice (the NFF reader refuses
// the first two already: here they are the preconditions, checked).
QCone coneRecord(uint32_t id, const LatticeCone& cone);

// The ray against the cone's record. With x = o + lambda d the quadric is
// F(q + 2 lambda d) = 4A lambda^2 + 4B lambda + C; disc = B^2 - AC < 0 is a miss
// (exactly: everything before the square root is exact). With s =
// floor(sqrt(disc)) and big = -(B + sgn(B) s) the roots are big / 2A and
// C / 2big (the second form of the quadratic formula: no cancellation, and a
// ray with A = 0, along a cylinder's axis or a cone's side, has its one root).
// The pipeline takes the nearer root that is ahead of the origin (> 0) and
// whose point lies between the planes, else the farther one if it is (a ray
// through the open end meets the inside). The hit is on the triangles' scale as
// a sphere's (t_num = num |d_dom|, det = den, within the segment); u_num is 0
// entering (F falls through 0), 1 leaving, v_num 0. Each root is the exact
// root of the record's quadric with sqrt(disc) taken as s: relative error
// below 1 / |big| (docs/quadrics.md).
IsectResult intersectCone(const QRay& ray, const QCone& cone);

}  // namespace lancer::fx
