#pragma once

// Records that cross the hardware boundary, written out bit by bit once.
//
// Each record has a field list (name, element width, element count, signedness)
// from which gen_rt_pkg emits the SystemVerilog `typedef struct packed`, and from
// which packWire()/unpackWire() place the C++ values at the same bit offsets.
// Layout rule (SystemVerilog's): the first field is most significant; within an
// array field `logic [N-1:0][W-1:0] f`, element 0 is least significant.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "golden/formats.h"

namespace lancer::fx {

struct FieldSpec {
  const char* name;
  int width;   // bits of one element
  int count;   // elements (1 for a scalar)
  bool isSigned;
  const char* doc;
};

struct RecordSpec {
  const char* name;        // SystemVerilog type name, ends in _t
  const char* widthParam;  // rt_pkg's localparam of its width: "ISECT_RAY_W"
  const char* doc;
  std::span<const FieldSpec> fields;
};

constexpr int recordBits(std::span<const FieldSpec> fields) {
  int bits = 0;
  for (const FieldSpec& f : fields) bits += f.width * f.count;
  return bits;
}
constexpr int wireWords(int bits) { return (bits + 31) / 32; }

// A localparam of rt_pkg: the name the RTL reads and its value.
struct PackageParam {
  const char* name;
  long long value;
};

// A record's width, as rt_pkg holds it.
constexpr PackageParam widthParam(const RecordSpec& record) {
  return {record.widthParam, recordBits(record.fields)};
}

// ---- isect_ray_t: a quantized ray, as the intersection pipeline sees it -------
inline constexpr FieldSpec kIsectRayFields[] = {
    {"ray_id", kRayIdBits, 1, false, "ray id, carried to the result"},
    {"org", kPosBits, 3, false, "origin on the position lattice, [0]=x"},
    {"dir", kDirBits, 3, true, "direction, dominant component = +-DIR_MAX"},
    {"t_max", kSegEndBits, 1, false, "segment end, dominant-axis displacement * 2^SEG_FRAC; all ones: none"},
    {"any_hit", 1, 1, false, "1: any hit on the segment answers (traversal units stop at the first)"},
};
// ---- isect_tri_t: a quantized triangle -----------------------------------------
inline constexpr FieldSpec kIsectTriFields[] = {
    {"prim_id", kPrimIdBits, 1, false, "triangle id, carried to the result"},
    {"v0", kPosBits, 3, false, "vertex 0 on the position lattice"},
    {"v1", kPosBits, 3, false, "vertex 1 (weight u)"},
    {"v2", kPosBits, 3, false, "vertex 2 (weight v)"},
};
// ---- isect_res_t: one pipeline result; all numeric fields zero on a miss -------
inline constexpr FieldSpec kIsectResFields[] = {
    {"ray_id", kRayIdBits, 1, false, "ray id of the request"},
    {"prim_id", kPrimIdBits, 1, false, "triangle id of the request"},
    {"hit", 1, 1, false, "1 if the ray hits the triangle at t > 0"},
    {"t_num", kTNumBits, 1, false, "t = t_num / (DIR_MAX * det)"},
    {"det", kDetAbsBits, 1, false, "|determinant|, > 0 on a hit"},
    {"u_num", kBaryBits, 1, false, "u = u_num / det (weight of v1)"},
    {"v_num", kBaryBits, 1, false, "v = v_num / det (weight of v2)"},
};

// ---- <unit>_visit_t: one structure element a traversal unit entered (`id`:
// cell_id, node_id), on its trace stream -------------------------------------------
constexpr std::array<FieldSpec, 2> traversalVisitFields(const char* id, int idBits, const char* idDoc) {
  return {{
      {"ray_id", kRayIdBits, 1, false, "ray id"},
      {id, idBits, 1, false, idDoc},
  }};
}

// A closest hit, field for field as isect_res_t after its flag (`flag`: the
// result's hit, a walk record's has_hit): a ray's result and a walk set aside
// carry it alike.
constexpr std::array<FieldSpec, 6> closestHitFields(const char* flag, const char* flagDoc, const char* primDoc) {
  return {{
      {flag, 1, 1, false, flagDoc},
      {"prim_id", kPrimIdBits, 1, false, primDoc},
      {"t_num", kTNumBits, 1, false, "as isect_res_t"},
      {"det", kDetAbsBits, 1, false, "as isect_res_t"},
      {"u_num", kBaryBits, 1, false, "as isect_res_t"},
      {"v_num", kBaryBits, 1, false, "as isect_res_t"},
  }};
}

// ---- <unit>_res_t: a ray's answer from a traversal unit: the
// structure elements it visited (`visited`: cells, nodes), the tests it issued
// (and of them the ray-quadric ones), and its closest hit, field for field as isect_res_t ---------------------------------
constexpr std::array<FieldSpec, 10> traversalResFields(const char* visited, const char* visitedDoc) {
  std::array<FieldSpec, 10> fields{{
      {"ray_id", kRayIdBits, 1, false, "ray id"},
      {visited, 32, 1, false, visitedDoc},
      {"tests", 32, 1, false, "ray-primitive tests issued"},
      {"quadric_tests", 32, 1, false, "of them ray-quadric (0 in a unit without rt_quadric)"},
  }};
  const auto hit = closestHitFields("hit", "1 if the ray hit a primitive", "closest primitive (zero on a miss)");
  for (size_t i = 0; i < hit.size(); ++i) fields[4 + i] = hit[i];
  return fields;
}

// ---- <unit>_walk_t: a walk set aside by the treelet schedule (docs/scheduling.md):
// the closest hit so far, field for field as isect_res_t, then the unit's own
// walk state `state` ------------------------------------------------------------------
inline constexpr int kWalkHitFields = int(closestHitFields("", "", "").size());
template <size_t N>
constexpr std::array<FieldSpec, kWalkHitFields + N> walkRecordFields(const std::array<FieldSpec, N>& state) {
  std::array<FieldSpec, kWalkHitFields + N> fields{};
  const auto hit = closestHitFields("has_hit", "1: the ray has a closest hit so far (the fields below); 0: none yet",
                                    "the closest hit so far: as isect_res_t (zero without one)");
  for (size_t i = 0; i < hit.size(); ++i) fields[i] = hit[i];
  for (size_t i = 0; i < N; ++i) fields[size_t(kWalkHitFields) + i] = state[i];
  return fields;
}

inline constexpr RecordSpec kIsectRay{"isect_ray_t", "ISECT_RAY_W", "a quantized ray", kIsectRayFields};
inline constexpr RecordSpec kIsectTri{"isect_tri_t", "ISECT_TRI_W", "a quantized triangle", kIsectTriFields};
inline constexpr RecordSpec kIsectRes{"isect_res_t", "ISECT_RES_W", "an intersection result", kIsectResFields};
// The intersection pipeline's records; each traversal unit lists its own
// (its descriptor's kRecords), and golden/units.h's allRecords() has them all.
inline constexpr RecordSpec kIsectRecords[] = {kIsectRay, kIsectTri, kIsectRes};

inline constexpr int kIsectRayBits = recordBits(kIsectRayFields);
inline constexpr int kIsectTriBits = recordBits(kIsectTriFields);
inline constexpr int kIsectResBits = recordBits(kIsectResFields);

// ---- The C++ views of the records ----------------------------------------------
struct QRay {
  uint32_t id = 0;
  std::array<int64_t, 3> org{};  // 0 .. kPosMax
  std::array<int64_t, 3> dir{};  // -kDirMax .. kDirMax
  uint64_t tMax = kSegEndNone;   // segment end (formats.h); kSegEndNone: none
  bool anyHit = false;           // shadow rays: the walk ends at the first region with a hit
  bool operator==(const QRay&) const = default;
  bool bounded() const { return tMax != kSegEndNone; }
};

struct QTriangle {
  uint32_t id = 0;
  std::array<std::array<int64_t, 3>, 3> v{};  // v[vertex][axis], 0 .. kPosMax
  bool operator==(const QTriangle&) const = default;
};

struct IsectResult {
  uint32_t rayId = 0;
  uint32_t primId = 0;
  bool hit = false;
  u128 tNum = 0;
  u128 det = 0;
  u128 uNum = 0;
  u128 vNum = 0;
  bool operator==(const IsectResult&) const = default;
};

// A record as bits: 32-bit words, least significant first (Verilator's VlWide order).
using Wire = std::vector<uint32_t>;

// Flattened field values of a record (arrays count each element).
constexpr size_t valueCount(std::span<const FieldSpec> fields) {
  size_t n = 0;
  for (const FieldSpec& f : fields) n += size_t(f.count);
  return n;
}

// Sizes known at compile time, for the allocation-free forms below.
inline constexpr size_t kIsectRayWords = size_t(wireWords(kIsectRayBits));
inline constexpr size_t kIsectTriWords = size_t(wireWords(kIsectTriBits));
inline constexpr size_t kIsectResWords = size_t(wireWords(kIsectResBits));
inline constexpr size_t kIsectRayValues = valueCount(kIsectRayFields);
inline constexpr size_t kIsectTriValues = valueCount(kIsectTriFields);
inline constexpr size_t kIsectResValues = valueCount(kIsectResFields);
using RayWire = std::array<uint32_t, kIsectRayWords>;
using TriWire = std::array<uint32_t, kIsectTriWords>;
using ResWire = std::array<uint32_t, kIsectResWords>;

// ---- Allocation-free packing (what the simulated devices use per record) ------
// Wire images go to / come from a caller's span of at least wireWords(bits)
// words; the words of the image are overwritten (the rest of the span is left
// alone). A span too short throws std::logic_error.
void packWire(const QRay& ray, std::span<uint32_t> wire);
void packWire(const QTriangle& tri, std::span<uint32_t> wire);
void packWire(const IsectResult& res, std::span<uint32_t> wire);
void unpackRay(std::span<const uint32_t> wire, QRay& ray);
void unpackTriangle(std::span<const uint32_t> wire, QTriangle& tri);
void unpackResult(std::span<const uint32_t> wire, IsectResult& res);

// The field values of a record, flattened in declaration order (arrays element 0 first).
std::array<u128, kIsectRayValues> fieldArray(const QRay& ray);
std::array<u128, kIsectTriValues> fieldArray(const QTriangle& tri);
std::array<u128, kIsectResValues> fieldArray(const IsectResult& res);

// Places flattened field values into a wire image by the field list, and back
// (signed fields are sign-extended on the way out). The one implementation of
// the bit layout: every form above and below goes through these two.
void packFields(std::span<const FieldSpec> fields, std::span<const u128> values, std::span<uint32_t> wire);
void unpackFields(std::span<const FieldSpec> fields, std::span<const uint32_t> wire, std::span<u128> values);

// ---- Convenience forms that return new storage (tests, reports, reproducers) --
Wire packWire(const QRay& ray);
Wire packWire(const QTriangle& tri);
Wire packWire(const IsectResult& res);
// (The three unpack forms return by value and allocate nothing either.)
QRay unpackRay(std::span<const uint32_t> wire);
QTriangle unpackTriangle(std::span<const uint32_t> wire);
IsectResult unpackResult(std::span<const uint32_t> wire);

std::vector<u128> fieldValues(const QRay& ray);
std::vector<u128> fieldValues(const QTriangle& tri);
std::vector<u128> fieldValues(const IsectResult& res);

Wire packFields(std::span<const FieldSpec> fields, std::span<const u128> values);
std::vector<u128> unpackFields(std::span<const FieldSpec> fields, std::span<const uint32_t> wire);

}  // namespace lancer::fx
