#pragma once

// The one source of truth for every fixed-point format of the hardware.
//
// Two parameters, set at configure time (cmake -DLANCER_POS_BITS=.. -DLANCER_DIR_BITS=..),
// determine every width below; the SystemVerilog package rt_pkg.sv is generated
// from this header by gen_rt_pkg (sw/golden/gen_rt_pkg.cpp), so the RTL, the
// SystemC models and the golden model cannot drift. A precision sweep is a
// rebuild with other values, not an edit. docs/number-formats.md derives each
// width and error bound. Each traversal unit's own formats sit beside its
// golden model, in the same way (grid_formats.h, octree_formats.h).

#include <cstdint>

#ifndef LANCER_POS_BITS
#error "LANCER_POS_BITS must be defined by the build (see cmake/NumberFormats.cmake)"
#endif
#ifndef LANCER_DIR_BITS
#error "LANCER_DIR_BITS must be defined by the build (see cmake/NumberFormats.cmake)"
#endif

namespace lancer::fx {

using i128 = __int128;
using u128 = unsigned __int128;

// ---- Primary formats -------------------------------------------------------
// Positions (vertices and ray origins): unsigned integers on a lattice of
// 2^PosBits points per axis spanning the scene's bounding cube. Error <= 1/2 unit.
inline constexpr int kPosBits = LANCER_POS_BITS;
// Directions: signed two's complement, scaled so the dominant component is
// exactly +-kDirMax; the others are rounded to nearest. kDirMax is the largest
// magnitude, so the most negative code -2^(DirBits-1) is never used.
inline constexpr int kDirBits = LANCER_DIR_BITS;
inline constexpr int64_t kPosMax = (int64_t(1) << kPosBits) - 1;
inline constexpr int64_t kDirMax = (int64_t(1) << (kDirBits - 1)) - 1;

// Identifiers travel with every record so traces, logs and reports name the ray.
inline constexpr int kRayIdBits = 32;
inline constexpr int kPrimIdBits = 32;

// ---- Intermediates of the intersection pipeline (all exact, no rounding) ----
// Signed width that holds any value whose magnitude is below 2^m.
constexpr int signedBitsFor(int m) { return m + 1; }
// a = v - o, |a| <= 2^P - 1 .................................... P+1 signed
inline constexpr int kRelBits = signedBitsFor(kPosBits);
// shear: ax = dz*a[kx] - dx*a[kz], |each product| < 2^(P+D-1) .. P+D+1 signed
inline constexpr int kShearBits = signedBitsFor(kPosBits + kDirBits);
// edge function: U = cx*by - cy*bx, |product| < 2^(2(P+D)) ....... 2(P+D)+2 signed
inline constexpr int kEdgeBits = signedBitsFor(2 * (kPosBits + kDirBits) + 1);
// det = U + V + W, |det| < 3 * 2^(2(P+D)+1) < 2^(2(P+D)+3) ........ 2(P+D)+4 signed
inline constexpr int kDetBits = signedBitsFor(2 * (kPosBits + kDirBits) + 3);
// T = U*az + V*bz + W*cz, |each product| < 2^(3P+2D+1), sum < 2^(3P+2D+3)
inline constexpr int kTBits = signedBitsFor(3 * kPosBits + 2 * kDirBits + 3);

// ---- Outputs: the un-normalized hit (Embree's U, V, T, absDen) --------------
// On a hit the signs are normalized so every output is non-negative:
//   t = t_num / (|d[kz]| * det),  u = u_num / det,  v = v_num / det,
// where |d[kz]| = kDirMax for every ray (the dominant component), so comparing
// two hits of the same ray is a cross-multiplication t_num1*det2 < t_num2*det1.
inline constexpr int kTNumBits = kTBits - 1;
inline constexpr int kDetAbsBits = kDetBits - 1;
inline constexpr int kBaryBits = kEdgeBits - 1;

// The golden model computes in int64 up to the shear and __int128 after it.
static_assert(kPosBits >= 4 && kDirBits >= 4, "formats narrower than 4 bits are meaningless");
static_assert(kShearBits <= 63, "shear must fit int64: lower LANCER_POS_BITS + LANCER_DIR_BITS");
static_assert(kTBits <= 127, "T must fit __int128: need 3*POS_BITS + 2*DIR_BITS <= 123");

// ---- The ray segment (docs/number-formats.md, "Segment end") -----------------
// A ray may end before the lattice's edge (a shadow ray at its light). Its end is
// a displacement along the dominant axis, in lattice units with kSegFracBits
// fraction bits: t_max = floor(2^F * |p_end - o|_kz). A hit's displacement is
// exactly t_num / det (t = t_num / (DIR_MAX * det), times |d[kz]| = DIR_MAX), so
// the hit counts iff t_num * 2^F <= t_max * det: an exact integer test, and a
// hit exactly at the end counts. A hit inside the lattice moves less than 2^P
// along any axis, so the all-ones code (>= 2^(P+1) - 2^-F) is "no end": no hit
// is ever beyond it and the units walk exactly as for an unbounded ray.
inline constexpr int kSegFracBits = 8;
inline constexpr int kSegEndBits = kPosBits + 1 + kSegFracBits;
inline constexpr uint64_t kSegEndNone = (uint64_t(1) << kSegEndBits) - 1;

// Memory image address width (every region: cells, index list, triangles).
#ifndef LANCER_MEM_ADDR_BITS
#define LANCER_MEM_ADDR_BITS 24
#endif
inline constexpr int kMemAddrBits = LANCER_MEM_ADDR_BITS;
// An index-list entry names a primitive: its top bit the kind (set: the
// quadric table's), the rest its place in that table (golden/primitives.h).
inline constexpr uint32_t kQuadricEntryBit = uint32_t(1) << 31;
static_assert(kMemAddrBits < 31, "an index entry's place lies below its kind bit");

// ---- Pipeline timing ---------------------------------------------------------
// Cycles from an accepted request to its result appearing on the output, with
// no backpressure. The RTL builds this many stages; the SystemC model delays by it.
inline constexpr int kIsectLatency = 6;
// Cycles from a traversal unit's exit-test grant to its answer reaching the
// slot (rt_trav_shell: the grant registered, the operands, two products, the
// comparison; one wide multiply a stage). The RTL builds these stages; the
// SystemC shell model delays the answer by them.
inline constexpr int kExitTestLatency = 5;
// Cycles from an intersection result leaving rt_isect to its closest-hit
// verdict reaching the walk (rt_closest_hit: the slot's record read and
// registered, the cross products, their difference; issue #35: the record's
// read and a product in one cycle were the traversal units' STA critical path).
inline constexpr int kClosestHitLatency = 2;

}  // namespace lancer::fx
