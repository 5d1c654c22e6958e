#pragma once

// Bit-accurate model of the quadric test (issue #40, docs/quadrics.md): a ray
// against a sphere or an NFF cone on the position lattice, in integers, as the
// quadric pipeline rt_quadric computes it. The result is an isect_res_t like a
// triangle's, on the same scale (t_num / det is the hit's displacement along
// the ray's dominant axis, in lattice units), so closerResult orders spheres,
// cones and triangles alike.

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

#include "golden/formats.h"
#include "golden/lattice.h"
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

// floor(sqrt(v)) of a non-negative 128-bit integer, by the digit-by-digit
// method (one result bit a step).
u128 isqrt(u128 v);

// a b / 2^e rounded to nearest, ties away from zero, for a product of up to
// 256 bits whose quotient fits 128: a cone's constant is 6P + 6 bits before
// its scale (150 at 24/24), beyond a 128-bit product.
u128 roundShiftProduct(u128 a, u128 b, int e);

// ---- The cone ----------------------------------------------------------------
// An NFF cone on the lattice: base center b and apex center a (0 .. kPosMax per
// axis, a != b), radii r0 at b and r1 at a (0 .. kPosMax lattice units, not
// both 0), open ends; a cylinder when r0 = r1. (NFF's negative radii, "inside
// visible", are the shader's business: the result says which side was hit.)
struct LatticeCone {
  std::array<int64_t, 3> base{}, apex{};
  int64_t baseRadius = 1, apexRadius = 1;
};

// K: the quadric part of a record is rounded to |Q_ij| <= 2^K. The largest K
// whose per-ray arithmetic stays in 128-bit integers (the discriminant,
// 2P + 2D + 2K + 10 bits signed: all 128 at 16/16, K = 27) and whose result
// fits the triangles' record (t_num 3P + 2D + 3 bits, det 2(P + D) + 3 bits:
// docs/quadrics.md, "The cone"), and whose constant k (2P + K + 4 bits
// signed) fits the record's 64-bit field: the last binds only at a wide P
// and a narrow D (24/4: K = 12).
// Of any widths, so that the sweep can refuse a width before building it; below
// kQuadricMinK the record cannot hold a cone (P >= 5 and P + D >= 12 within
// the widths' 4..24; cmake/NumberFormats.cmake keeps its own copy of the rule).
constexpr int quadricCoefficientBits(int posBits, int dirBits) {
  return std::min({59 - posBits - dirBits, posBits + dirBits - 4, 2 * posBits - 2, 60 - 2 * posBits});
}
inline constexpr int kQuadricMinK = 8;
inline constexpr int kQuadricK = quadricCoefficientBits(kPosBits, kDirBits);

// ---- The record: one for spheres and cones ------------------------------------
// A quadric q'Qq + 2g'q + k = 0 in the frame q = 2x - S (x on the lattice; the
// frame doubled so that a cone's axis midpoint and a sphere's center, where
// the rounding matters least, are integers), cut by two planes: the pipeline
// keeps points with |q.w| <= W, W = w.w.
//  - a cone (coneRecord): S = a + b, w = a - b, and the exact quadric
//      F(q) = W^2 |q|^2 - W (q.w)^2 - ((r0 + r1) W + (r1 - r0)(q.w))^2
//           = 4 W^2 (radial distance^2 - radius at the point's height^2),
//    divided by 2^e and rounded to integers so that |Q_ij| <= 2^K: the record
//    states exactly the quadric the pipeline traces, within the bound of
//    docs/quadrics.md of the scene's cone;
//  - a sphere (sphereRecord): S = 2c, w = 0 (no planes: 0 <= 0 always), Q = I,
//    g = 0, k = -4r^2, so F(q) = 4(|x - c|^2 - r^2), exactly.
// Record field widths (signed where they can be negative):
inline constexpr int kQuadricAxisSumBits = kPosBits + 1;                  // S_i
inline constexpr int kQuadricAxisBits = kPosBits + 1;                     // w_i, signed
inline constexpr int kQuadricAxisLen2Bits = 2 * kPosBits + 2;             // W
inline constexpr int kQuadricCoefBits = kQuadricK + 2;                    // Q_ij, signed
inline constexpr int kQuadricLinBits = kPosBits + kQuadricK + 3;          // g_i, signed
inline constexpr int kQuadricConstBits = 2 * kPosBits + kQuadricK + 4;    // k, signed
struct QQuadric {
  uint32_t id = 0;
  std::array<int64_t, 3> axisSum{};  // S: a + b (cone), 2c (sphere)
  std::array<int64_t, 3> axis{};     // w = a - b (cone), 0 (sphere)
  int64_t axisLen2 = 0;              // W = w.w
  std::array<int64_t, 6> quad{};     // Q: xx, yy, zz, yz, xz, xy; |Q_ij| <= 2^K
  std::array<int64_t, 3> lin{};      // g: |g_i| <= 2^(P+K+1)
  int64_t constant = 0;              // k <= 0: |k| <= 2^(2P+K+2)
  int scaleExp = 0;                  // e (host only, for the error bound): exact F = 2^e times the record's, within rounding
  // Host only, for the structures' builders: a lattice box holding every point
  // of the surface the record traces (sphereRecord, coneRecord).
  LatticeBox bounds;
  bool operator==(const QQuadric&) const = default;
  int64_t quadAt(int i, int j) const { return i == j ? quad[size_t(i)] : quad[size_t(6 - i - j)]; }
};

// The record of a lattice sphere (bounds: c +- (r + 1), a unit for the root's
// rounding, so every hit the pipeline computes lies in them). Throws std::invalid_argument off the lattice
// or for a radius outside 1 .. kPosMax.
QQuadric sphereRecord(const QSphere& sphere);

// The record of a lattice cone; its bounds hold both end discs widened by the
// record's rounding (docs/quadrics.md, "The cone": |rho^2 - R^2| within
// max(1, tau^2) (sum |q_i| + 1)^2 / 2^(K+2), |q_i| < 2^(P+1) on the lattice)
// and a unit, as a sphere's. Throws std::invalid_argument on what is no cone
// (both radii 0, base = apex) or lies off the lattice (the NFF reader refuses
// the first two already: here they are the preconditions, checked).
QQuadric coneRecord(uint32_t id, const LatticeCone& cone);

// ---- The test ---------------------------------------------------------------
// The widths of the quadric pipeline, from P, D and K (bounds on magnitudes;
// every quantity is exact until the square root, and the pipeline computes
// each modulo its width, exact because the value fits):
//   q = 2o - S                       |q_i| < 2^(P+1)         P + 2 bits signed
//   A = d'Qd                         |A| < 2^(K+2D+2)       K + 2D + 3 bits signed
//   B = d'(Qq + g)                   |B| < 2^(P+D+K+4)      P + D + K + 5 bits signed
//   C = q'Qq + 2g'q + k              |C| < 2^(2P+K+6)       2P + K + 7 bits signed
//   disc = B^2 - A C                 |disc| < 2^(2P+2D+2K+9)
//   s = floor(sqrt(disc))            s < 2^(P+D+K+5)
//   big = -(B + sgn(B) s)            |big| < 2^(P+D+K+6)
//   roots big / 2A, C / 2big         numerators as big and C, denominators < 2^(P+D+K+7)
//   heights q.w, d.w                 < 2^(2P+3), < 2^(P+D+1)
//   planes |(q.w) den + 2 num (d.w)| <= W den              < 2^(3P+D+K+11)
inline constexpr int kQuadricQBits = kPosBits + 2;
inline constexpr int kQuadricABits = kQuadricK + 2 * kDirBits + 3;
inline constexpr int kQuadricBBits = kPosBits + kDirBits + kQuadricK + 5;
inline constexpr int kQuadricCBits = 2 * kPosBits + kQuadricK + 7;
inline constexpr int kQuadricDiscBits = 2 * kPosBits + 2 * kDirBits + 2 * kQuadricK + 10;
inline constexpr int kQuadricRootBits = kPosBits + kDirBits + kQuadricK + 5;
inline constexpr int kQuadricNumBits = std::max(kQuadricBBits + 2, kQuadricCBits);  // big or C, signed
inline constexpr int kQuadricDenBits = kPosBits + kDirBits + kQuadricK + 7;
inline constexpr int kQuadricOriginHeightBits = 2 * kPosBits + 4;  // q.w, signed
inline constexpr int kQuadricDirHeightBits = kPosBits + kDirBits + 2;  // d.w, signed
inline constexpr int kQuadricPlaneBits = 3 * kPosBits + kDirBits + kQuadricK + 12;
static_assert(kQuadricK >= kQuadricMinK, "too few bits for the quadric");
static_assert(kQuadricDiscBits <= 128, "the discriminant is computed in 128-bit integers");
static_assert(kQuadricPlaneBits <= 127, "the plane test is computed in 128-bit integers");
static_assert(kQuadricConstBits <= 64, "the record's constant is a 64-bit integer");
static_assert(5 * kPosBits + 3 <= 126, "the host computes a cone's quadric and linear terms in 128-bit integers");
static_assert(kQuadricNumBits + kDirBits - 2 <= kTNumBits && kQuadricDenBits <= kDetAbsBits,
              "a quadric's hit fits the triangles' result record");

// The pipeline's depth (rt_quadric): seven stages compute the discriminant,
// the square root takes kQuadricRootStep result bits a stage, four choose the
// root (docs/quadrics.md, "The pipeline").
inline constexpr int kQuadricRootStep = 2;
inline constexpr int kQuadricRootStages = (kQuadricRootBits + kQuadricRootStep - 1) / kQuadricRootStep;
inline constexpr int kQuadricLatency = 7 + kQuadricRootStages + 4;
static_assert(kQuadricDiscBits == 2 * kQuadricRootBits, "the square root takes two discriminant bits a result bit");

// ---- isect_quadric_t: a quadric's record as the pipeline reads it -------------
inline constexpr FieldSpec kIsectQuadricFields[] = {
    {"prim_id", kPrimIdBits, 1, false, "primitive id, carried to the result"},
    {"axis_sum", kQuadricAxisSumBits, 3, false, "S: the frame's origin doubled (a + b, or 2c)"},
    {"axis", kQuadricAxisBits, 3, true, "w = a - b (0 for a sphere)"},
    {"axis_len2", kQuadricAxisLen2Bits, 1, false, "W = w.w"},
    {"quad", kQuadricCoefBits, 6, true, "Q: xx, yy, zz, yz, xz, xy"},
    {"lin", kQuadricLinBits, 3, true, "g"},
    {"konst", kQuadricConstBits, 1, true, "k"},
};
inline constexpr RecordSpec kIsectQuadric{"isect_quadric_t", "ISECT_QUADRIC_W", "a quadric's record",
                                          kIsectQuadricFields};
inline constexpr int kIsectQuadricBits = recordBits(kIsectQuadricFields);
inline constexpr size_t kIsectQuadricValues = valueCount(kIsectQuadricFields);
// rt_pkg's parameters of the quadric pipeline.
inline constexpr PackageParam kQuadricPkgParams[] = {
    {"QUADRIC_K", kQuadricK},
    {"QUADRIC_AXIS_SUM_W", kQuadricAxisSumBits},
    {"QUADRIC_AXIS_W", kQuadricAxisBits},
    {"QUADRIC_AXIS_LEN2_W", kQuadricAxisLen2Bits},
    {"QUADRIC_COEF_W", kQuadricCoefBits},
    {"QUADRIC_LIN_W", kQuadricLinBits},
    {"QUADRIC_CONST_W", kQuadricConstBits},
    {"QUADRIC_Q_W", kQuadricQBits},
    {"QUADRIC_A_W", kQuadricABits},
    {"QUADRIC_B_W", kQuadricBBits},
    {"QUADRIC_C_W", kQuadricCBits},
    {"QUADRIC_DISC_W", kQuadricDiscBits},
    {"QUADRIC_ROOT_W", kQuadricRootBits},
    {"QUADRIC_NUM_W", kQuadricNumBits},
    {"QUADRIC_DEN_W", kQuadricDenBits},
    {"QUADRIC_OH_W", kQuadricOriginHeightBits},
    {"QUADRIC_DH_W", kQuadricDirHeightBits},
    {"QUADRIC_PLANE_W", kQuadricPlaneBits},
    {"QUADRIC_ROOT_STEP", kQuadricRootStep},
    {"QUADRIC_ROOT_STAGES", kQuadricRootStages},
    {"QUADRIC_LATENCY", kQuadricLatency},
    widthParam(kIsectQuadric),
};
// The record's field values in declaration order (signed fields as two's
// complement), for packFields / packWire.
std::array<u128, kIsectQuadricValues> fieldArray(const QQuadric& quadric);
void packWire(const QQuadric& quadric, std::span<uint32_t> wire);
// A record from its wire image (scaleExp and bounds, the host's, are 0).
QQuadric unpackQuadric(std::span<const uint32_t> wire);

// The ray against a quadric's record. With x = o + lambda d the quadric is
// F(q + 2 lambda d) = 4A lambda^2 + 4B lambda + C; disc = B^2 - AC < 0 is a miss
// (exactly: everything before the square root is exact). With s =
// floor(sqrt(disc)) and big = -(B + sgn(B) s) the roots are big / 2A and
// C / 2big (the second form of the quadratic formula: no cancellation, and a
// ray with A = 0, along a cylinder's axis or a cone's side, has its one root).
// The pipeline takes the nearer root that is ahead of the origin (> 0) and
// whose point lies between the planes, else the farther one if it is (a ray
// through a cone's open end meets the inside; a ray from inside a sphere
// leaves it). The hit is on the triangles' scale (t_num = num |d_dom|,
// det = den: t_num / det is the displacement along the ray's dominant axis in
// lattice units, as a triangle's), within the segment as a triangle's is
// (t_num 2^F <= t_max det), so closerResult orders quadrics and triangles
// alike; u_num is 0 entering (F falls through 0), 1 leaving, v_num 0. Each
// root is the exact root of the record's quadric with sqrt(disc) taken as s:
// relative error below 1 / |big| (docs/quadrics.md).
IsectResult intersectQuadric(const QRay& ray, const QQuadric& quadric);

}  // namespace lancer::fx
