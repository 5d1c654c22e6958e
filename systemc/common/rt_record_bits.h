#pragma once

// Fast access to the fields of a record's wire image, for the per-cycle paths
// of the SystemC models (child groups, triangles, visits): the field positions
// are computed once, at compile time, from the record's field list
// (sw/golden/records.h, the one source of the layout), so nothing here knows a
// width. fx::packFields / fx::unpackFields read the same layout generically
// (with span checks, one field at a time), which costs more per call than the
// whole rest of a cycle of the octree model; records.cpp's own unrolled
// packers serve only the isect records.
//
// Layout (SystemVerilog's packed structs): the first field is most
// significant; within an array field element 0 is least significant; bit i of
// the record is bit i%32 of word i/32.

#include <array>
#include <cstdint>
#include <span>

#include "golden/records.h"
#include "isect/rt_isect_types.h"

namespace lancer::sc {

struct rt_field_slot {
  int lsb = 0;    // position of the value's least significant bit in the record
  int width = 0;  // bits
  bool isSigned = false;
};

// The slot of every flattened value of a record (arrays: one per element), in
// fx::packFields' value order; N = fx::valueCount(fields).
template <size_t N>
constexpr std::array<rt_field_slot, N> fieldSlots(std::span<const fx::FieldSpec> fields) {
  std::array<rt_field_slot, N> slots{};
  int top = fx::recordBits(fields);
  size_t i = 0;
  for (const fx::FieldSpec& f : fields) {
    top -= f.width * f.count;
    for (int e = 0; e < f.count && i < N; ++e) slots[i++] = rt_field_slot{top + e * f.width, f.width, f.isSigned};
  }
  return slots;
}

template <const auto& Fields>
inline constexpr auto kFieldSlots = fieldSlots<fx::valueCount(Fields)>(Fields);

// Bits lsb .. lsb+width-1 of a wire image, width 1..64 (zero-extended).
inline uint64_t getBits64(const uint32_t* wire, int lsb, int width) {
  const int first = lsb >> 5, shift = lsb & 31;
  uint64_t v = 0;
  if (width + shift <= 64) {  // within two words (most fields): no 128-bit shifts
    v = wire[first];
    if (width + shift > 32) v |= uint64_t(wire[first + 1]) << 32;
    v >>= shift;
  } else {
    fx::u128 acc = 0;
    for (int k = 0; k * 32 < width + shift; ++k) acc |= fx::u128(wire[first + k]) << (32 * k);
    v = uint64_t(acc >> shift);
  }
  return width >= 64 ? v : v & ((uint64_t(1) << width) - 1);
}

// ORs `value` (width 1..64 bits) into bits lsb .. lsb+width-1 of a zeroed wire image.
inline void putBits64(uint32_t* wire, int lsb, int width, uint64_t value) {
  if (width < 64) value &= (uint64_t(1) << width) - 1;
  const int first = lsb >> 5, shift = lsb & 31;
  const fx::u128 acc = fx::u128(value) << shift;
  for (int k = 0; k * 32 < width + shift; ++k) wire[first + k] |= uint32_t(acc >> (32 * k));
}

// Value I of record Fields from its wire image (signed fields sign-extended).
template <const auto& Fields, size_t I>
inline int64_t getField(const uint32_t* wire) {
  constexpr rt_field_slot s = kFieldSlots<Fields>[I];
  static_assert(s.width <= 64, "getField reads fields of up to 64 bits");
  const uint64_t raw = getBits64(wire, s.lsb, s.width);
  if constexpr (s.isSigned && s.width < 64) {
    const uint64_t sign = uint64_t(1) << (s.width - 1);
    return int64_t((raw ^ sign) - sign);
  } else {
    return int64_t(raw);
  }
}

template <const auto& Fields, size_t I>
inline void putField(uint32_t* wire, uint64_t value) {
  constexpr rt_field_slot s = kFieldSlots<Fields>[I];
  static_assert(s.width <= 64, "putField writes fields of up to 64 bits");
  putBits64(wire, s.lsb, s.width, value);
}

// Wire image -> an existing port value, in place (toPort's result without
// constructing an sc_bv, which allocates): for the ports written every cycle.
template <int W>
inline void assignPort(vl_port_t<W>& port, std::span<const uint32_t> wire) {
  if constexpr (W <= 64) {
    port = toPort<W>(wire);
  } else {
    for (int i = 0; i < fx::wireWords(W); ++i) port.set_word(i, wire[size_t(i)]);
    port.clean_tail();
  }
}

}  // namespace lancer::sc
