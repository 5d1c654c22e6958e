#include "golden/records.h"

#include <algorithm>
#include <stdexcept>

namespace lancer::fx {

namespace {

u128 lowBits(u128 value, int width) {
  return width >= 128 ? value : (value & ((u128(1) << width) - 1));
}

uint32_t lowMask(int bits) { return bits >= 32 ? ~uint32_t(0) : ((uint32_t(1) << bits) - 1); }

// Word-wise so that packing stays cheap next to a Verilated clock edge.
void putBits(Wire& wire, int lsb, int width, u128 value) {
  value = lowBits(value, width);
  while (width > 0) {
    const int offset = lsb % 32;
    const int take = std::min(32 - offset, width);
    wire[size_t(lsb / 32)] |= (uint32_t(value) & lowMask(take)) << offset;
    value >>= take;
    lsb += take;
    width -= take;
  }
}

u128 getBits(std::span<const uint32_t> wire, int lsb, int width) {
  u128 value = 0;
  for (int done = 0; done < width;) {
    const int offset = (lsb + done) % 32;
    const int take = std::min(32 - offset, width - done);
    value |= u128((wire[size_t((lsb + done) / 32)] >> offset) & lowMask(take)) << done;
    done += take;
  }
  return value;
}

u128 signExtend(u128 value, int width) {
  if (width < 128 && ((value >> (width - 1)) & 1)) value |= ~((u128(1) << width) - 1);
  return value;
}

template <size_t N>
std::array<int64_t, N> takeSigned(const std::vector<u128>& values, size_t& at) {
  std::array<int64_t, N> out{};
  for (auto& v : out) v = int64_t(i128(values[at++]));
  return out;
}

}  // namespace

Wire packFields(std::span<const FieldSpec> fields, std::span<const u128> values) {
  const int total = recordBits(fields);
  Wire wire(size_t(wireWords(total)), 0);
  int msb = total;  // the first field is the most significant
  size_t at = 0;
  for (const FieldSpec& f : fields) {
    msb -= f.width * f.count;
    for (int e = 0; e < f.count; ++e) {
      if (at >= values.size()) throw std::logic_error("packFields: too few values");
      putBits(wire, msb + e * f.width, f.width, values[at++]);
    }
  }
  if (at != values.size()) throw std::logic_error("packFields: too many values");
  return wire;
}

std::vector<u128> unpackFields(std::span<const FieldSpec> fields, std::span<const uint32_t> wire) {
  std::vector<u128> values;
  int msb = recordBits(fields);
  for (const FieldSpec& f : fields) {
    msb -= f.width * f.count;
    for (int e = 0; e < f.count; ++e) {
      const u128 raw = getBits(wire, msb + e * f.width, f.width);
      values.push_back(f.isSigned ? signExtend(raw, f.width) : raw);
    }
  }
  return values;
}

std::vector<u128> fieldValues(const QRay& r) {
  return {r.id, u128(r.org[0]), u128(r.org[1]), u128(r.org[2]),
          u128(i128(r.dir[0])), u128(i128(r.dir[1])), u128(i128(r.dir[2]))};
}

std::vector<u128> fieldValues(const QTriangle& t) {
  std::vector<u128> values{t.id};
  for (const auto& vertex : t.v)
    for (int64_t c : vertex) values.push_back(u128(c));
  return values;
}

std::vector<u128> fieldValues(const IsectResult& r) {
  return {r.rayId, r.primId, r.hit ? 1u : 0u, r.tNum, r.det, r.uNum, r.vNum};
}

Wire packWire(const QRay& ray) { return packFields(kIsectRayFields, fieldValues(ray)); }
Wire packWire(const QTriangle& tri) { return packFields(kIsectTriFields, fieldValues(tri)); }
Wire packWire(const IsectResult& res) { return packFields(kIsectResFields, fieldValues(res)); }

QRay unpackRay(std::span<const uint32_t> wire) {
  const auto values = unpackFields(kIsectRayFields, wire);
  QRay ray;
  size_t at = 0;
  ray.id = uint32_t(values[at++]);
  ray.org = takeSigned<3>(values, at);
  ray.dir = takeSigned<3>(values, at);
  return ray;
}

QTriangle unpackTriangle(std::span<const uint32_t> wire) {
  const auto values = unpackFields(kIsectTriFields, wire);
  QTriangle tri;
  size_t at = 0;
  tri.id = uint32_t(values[at++]);
  for (auto& vertex : tri.v) vertex = takeSigned<3>(values, at);
  return tri;
}

IsectResult unpackResult(std::span<const uint32_t> wire) {
  const auto values = unpackFields(kIsectResFields, wire);
  return IsectResult{uint32_t(values[0]), uint32_t(values[1]), values[2] != 0,
                     values[3], values[4], values[5], values[6]};
}

}  // namespace lancer::fx
