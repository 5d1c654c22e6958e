#include "golden/records.h"

#include "golden/record_bits.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace lancer::fx {

namespace {

using namespace wire_bits;

void checkSpans(std::span<const FieldSpec> fields, size_t values, size_t words, const char* what) {
  if (words < size_t(wireWords(recordBits(fields)))) throw std::logic_error(std::string(what) + ": wire span too short");
  if (values != valueCount(fields)) throw std::logic_error(std::string(what) + ": wrong number of values");
}

template <size_t N, size_t M>
std::array<int64_t, N> takeSigned(const std::array<u128, M>& values, size_t& at) {
  std::array<int64_t, N> out{};
  for (auto& v : out) v = int64_t(i128(values[at++]));
  return out;
}

}  // namespace

// ---- Allocation-free forms ------------------------------------------------------

void packFields(std::span<const FieldSpec> fields, std::span<const u128> values, std::span<uint32_t> wire) {
  checkSpans(fields, values.size(), wire.size(), "packFields");
  std::fill_n(wire.begin(), wireWords(recordBits(fields)), 0u);
  forEachSlot(fields, [&](size_t i, Slot slot) { putBits(wire, slot.lsb, slot.width, values[i]); });
}

void unpackFields(std::span<const FieldSpec> fields, std::span<const uint32_t> wire, std::span<u128> values) {
  checkSpans(fields, values.size(), wire.size(), "unpackFields");
  forEachSlot(fields, [&](size_t i, Slot slot) {
    const u128 raw = getBits(wire, slot.lsb, slot.width);
    values[i] = slot.isSigned ? signExtend(raw, slot.width) : raw;
  });
}

std::array<u128, kIsectRayValues> fieldArray(const QRay& r) {
  return {r.id, u128(r.org[0]), u128(r.org[1]), u128(r.org[2]),
          u128(i128(r.dir[0])), u128(i128(r.dir[1])), u128(i128(r.dir[2])), r.tMax, r.anyHit ? 1u : 0u};
}

std::array<u128, kIsectTriValues> fieldArray(const QTriangle& t) {
  std::array<u128, kIsectTriValues> values{};
  size_t at = 0;
  values[at++] = t.id;
  for (const auto& vertex : t.v)
    for (int64_t c : vertex) values[at++] = u128(c);
  return values;
}

std::array<u128, kIsectResValues> fieldArray(const IsectResult& r) {
  return {r.rayId, r.primId, r.hit ? 1u : 0u, r.tNum, r.det, r.uNum, r.vNum};
}

void packWire(const QRay& ray, std::span<uint32_t> wire) { packFixed<kIsectRayFields>(fieldArray(ray), wire); }
void packWire(const QTriangle& tri, std::span<uint32_t> wire) { packFixed<kIsectTriFields>(fieldArray(tri), wire); }
void packWire(const IsectResult& res, std::span<uint32_t> wire) {
  packFixed<kIsectResFields>(fieldArray(res), wire);
}

void unpackRay(std::span<const uint32_t> wire, QRay& ray) {
  const auto values = unpackFixed<kIsectRayFields>(wire);
  size_t at = 0;
  ray.id = uint32_t(values[at++]);
  ray.org = takeSigned<3>(values, at);
  ray.dir = takeSigned<3>(values, at);
  ray.tMax = uint64_t(values[at++]);
  ray.anyHit = values[at++] != 0;
}

void unpackTriangle(std::span<const uint32_t> wire, QTriangle& tri) {
  const auto values = unpackFixed<kIsectTriFields>(wire);
  size_t at = 0;
  tri.id = uint32_t(values[at++]);
  for (auto& vertex : tri.v) vertex = takeSigned<3>(values, at);
}

void unpackResult(std::span<const uint32_t> wire, IsectResult& res) {
  const auto values = unpackFixed<kIsectResFields>(wire);
  res = IsectResult{uint32_t(values[0]), uint32_t(values[1]), values[2] != 0,
                    values[3], values[4], values[5], values[6]};
}

// ---- Forms that return new storage: the ones above, into a fresh buffer ---------

Wire packFields(std::span<const FieldSpec> fields, std::span<const u128> values) {
  Wire wire(size_t(wireWords(recordBits(fields))));
  packFields(fields, values, std::span<uint32_t>(wire));
  return wire;
}

std::vector<u128> unpackFields(std::span<const FieldSpec> fields, std::span<const uint32_t> wire) {
  std::vector<u128> values(valueCount(fields));
  unpackFields(fields, wire, std::span<u128>(values));
  return values;
}

template <typename Record>
std::vector<u128> toVector(const Record& record) {
  const auto values = fieldArray(record);
  return {values.begin(), values.end()};
}
std::vector<u128> fieldValues(const QRay& r) { return toVector(r); }
std::vector<u128> fieldValues(const QTriangle& t) { return toVector(t); }
std::vector<u128> fieldValues(const IsectResult& r) { return toVector(r); }

template <typename Record>
Wire toWire(const Record& record, int bits) {
  Wire wire(size_t(wireWords(bits)));
  packWire(record, std::span<uint32_t>(wire));
  return wire;
}
Wire packWire(const QRay& ray) { return toWire(ray, kIsectRayBits); }
Wire packWire(const QTriangle& tri) { return toWire(tri, kIsectTriBits); }
Wire packWire(const IsectResult& res) { return toWire(res, kIsectResBits); }

QRay unpackRay(std::span<const uint32_t> wire) {
  QRay ray;
  unpackRay(wire, ray);
  return ray;
}

QTriangle unpackTriangle(std::span<const uint32_t> wire) {
  QTriangle tri;
  unpackTriangle(wire, tri);
  return tri;
}

IsectResult unpackResult(std::span<const uint32_t> wire) {
  IsectResult res;
  unpackResult(wire, res);
  return res;
}

}  // namespace lancer::fx
