#pragma once

// Bit-accurate model of the quadric test (issue #40, docs/quadrics.md): a ray
// against a sphere on the position lattice, in integers, as the quadric
// pipeline will compute it. The result is an isect_res_t like a triangle's, on
// the same scale (t_num / det is the hit's displacement along the ray's
// dominant axis, in lattice units), so closerResult orders spheres and
// triangles alike.

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

}  // namespace lancer::fx
