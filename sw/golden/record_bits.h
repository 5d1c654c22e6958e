#pragma once

// The bit layout of a record on the wire, once (golden/records.h states the
// rule): where each flattened field value sits, and the word-by-word moves of
// a value in and out of a wire image. records.cpp builds the generic and the
// fixed records' packing on it; a unit's node, configuration and result
// records (golden/unit.h) are packed with packFixed and unpackFixed too.

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <utility>

#include "golden/records.h"

namespace lancer::fx::wire_bits {

constexpr u128 lowBits(u128 value, int width) {
  return width >= 128 ? value : (value & ((u128(1) << width) - 1));
}

// Word by word, so that packing stays cheap next to a Verilated clock edge: bits
// [lsb, lsb + width) of the image span words lsb/32 .. (lsb+width-1)/32, and
// image word w holds value bits from 32w - lsb on. The trip count is affine in
// lsb and width, so with the constants of the fixed records below the loop
// unrolls into a few shifts.
inline void putBits(std::span<uint32_t> wire, int lsb, int width, u128 value) {
  value = lowBits(value, width);
  const int last = (lsb + width - 1) / 32;
  for (int w = lsb / 32; w <= last; ++w) {
    const int at = 32 * w - lsb;  // negative for the first word unless lsb is word-aligned
    wire[size_t(w)] |= uint32_t(at >= 0 ? value >> at : value << -at);
  }
}

inline u128 getBits(std::span<const uint32_t> wire, int lsb, int width) {
  u128 value = 0;
  const int last = (lsb + width - 1) / 32;
  for (int w = lsb / 32; w <= last; ++w) {
    const int at = 32 * w - lsb;
    const u128 word = wire[size_t(w)];
    value |= at >= 0 ? word << at : word >> -at;
  }
  return lowBits(value, width);
}

constexpr u128 signExtend(u128 value, int width) {
  if (width < 128 && ((value >> (width - 1)) & 1)) value |= ~((u128(1) << width) - 1);
  return value;
}

// Where one flattened field value sits in the wire image.
struct Slot {
  int lsb = 0;
  int width = 0;
  bool isSigned = false;
};

// The bit layout, once: the first field is the most significant, element 0 of
// an array field is the least significant element. fn(index, slot) is called
// for every flattened value in declaration order. Used at run time by the
// generic forms and at compile time for the slot tables of the fixed records.
template <typename Fn>
constexpr void forEachSlot(std::span<const FieldSpec> fields, Fn&& fn) {
  int msb = recordBits(fields);
  size_t at = 0;
  for (const FieldSpec& f : fields) {
    msb -= f.width * f.count;
    for (int e = 0; e < f.count; ++e) fn(at++, Slot{msb + e * f.width, f.width, f.isSigned});
  }
}

// ---- The fixed records: the same layout, unrolled at compile time ---------------

template <const auto& Fields>
inline constexpr auto kSlots = [] {
  std::array<Slot, valueCount(Fields)> slots{};
  forEachSlot(Fields, [&](size_t i, Slot slot) { slots[i] = slot; });
  return slots;
}();

template <const auto& Fields>
void packFixed(const std::array<u128, valueCount(Fields)>& values, std::span<uint32_t> wire) {
  constexpr auto& slots = kSlots<Fields>;
  constexpr size_t words = size_t(wireWords(recordBits(Fields)));
  if (wire.size() < words) throw std::logic_error("packWire: wire span too short");
  std::fill_n(wire.begin(), words, 0u);
  [&]<size_t... I>(std::index_sequence<I...>) {
    (putBits(wire, slots[I].lsb, slots[I].width, values[I]), ...);
  }(std::make_index_sequence<slots.size()>{});
}

template <const auto& Fields>
std::array<u128, valueCount(Fields)> unpackFixed(std::span<const uint32_t> wire) {
  constexpr auto& slots = kSlots<Fields>;
  if (wire.size() < size_t(wireWords(recordBits(Fields)))) throw std::logic_error("unpack: wire span too short");
  std::array<u128, valueCount(Fields)> values;
  [&]<size_t... I>(std::index_sequence<I...>) {
    ((values[I] = slots[I].isSigned ? signExtend(getBits(wire, slots[I].lsb, slots[I].width), slots[I].width)
                                    : getBits(wire, slots[I].lsb, slots[I].width)),
     ...);
  }(std::make_index_sequence<slots.size()>{});
  return values;
}

// A record of at most 128 bits as one value (a field of a wider record: a
// walk record's node references), and back.
template <const auto& Fields>
u128 packValue(const std::array<u128, valueCount(Fields)>& values) {
  static_assert(recordBits(Fields) <= 128, "packValue: the record is wider than 128 bits");
  std::array<uint32_t, 4> wire{};
  packFixed<Fields>(values, wire);
  return u128(wire[0]) | (u128(wire[1]) << 32) | (u128(wire[2]) << 64) | (u128(wire[3]) << 96);
}
template <const auto& Fields>
std::array<u128, valueCount(Fields)> unpackValue(u128 value) {
  static_assert(recordBits(Fields) <= 128, "unpackValue: the record is wider than 128 bits");
  const std::array<uint32_t, 4> wire{uint32_t(value), uint32_t(value >> 32), uint32_t(value >> 64),
                                     uint32_t(value >> 96)};
  return unpackFixed<Fields>(wire);
}

}  // namespace lancer::fx::wire_bits
