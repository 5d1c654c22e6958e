#pragma once

// A port held as a plain value: what the SystemC models read and write when
// they are stepped directly (the fast path, docs/systemc.md) rather than
// bound to sc_signals. rt_value<T> has sc_in's read() and sc_out's write(),
// so a model's code reads the same on either binding, and a Verilated top's
// assignment and conversion, so the run loop that clocks a Verilated model
// clocks it too. A write is seen at once: there are no delta cycles, the
// caller orders evaluation (comb() after the inputs, cycle() at the edge).
//
// value_t<W> is the type of a W-bit value: bool, uint32_t, uint64_t up to 64
// bits (as Verilator's --sc types) and above, the record's wire image in
// 32-bit words, least significant first (as Verilator's C++ VlWide and
// fx::Wire), so that no sc_bv sits on the hot path.

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <type_traits>

namespace lancer::sc {

template <class T>
class rt_value {
 public:
  rt_value() = default;
  explicit rt_value(const char* /*name*/) {}  // sc_in's constructor: a value port has no name

  const T& read() const { return value; }
  void write(const T& v) { value = v; }
  operator const T&() const { return value; }  // NOLINT(google-explicit-constructor): a Verilated top's port
  rt_value& operator=(const T& v) {
    value = v;
    return *this;
  }

  T value{};
};

constexpr size_t valueWords(int width) { return size_t((width + 31) / 32); }

template <int W>
using value_t =
    std::conditional_t<(W == 1), bool,
                       std::conditional_t<(W <= 32), uint32_t,
                                          std::conditional_t<(W <= 64), uint64_t, std::array<uint32_t, valueWords(W)>>>>;

// Wire image -> value (bits above W dropped), and back into the first
// valueWords(W) words of `wire`.
template <int W>
value_t<W> toValue(std::span<const uint32_t> wire) {
  if constexpr (W == 1) {
    return (wire[0] & 1u) != 0;
  } else if constexpr (W <= 32) {
    return W == 32 ? wire[0] : wire[0] & ((uint32_t(1) << (W % 32)) - 1);
  } else if constexpr (W <= 64) {
    const uint64_t v = uint64_t(wire[0]) | (uint64_t(wire[1]) << 32);
    return W == 64 ? v : v & ((uint64_t(1) << (W % 64)) - 1);
  } else {
    value_t<W> v{};
    for (size_t i = 0; i < v.size(); ++i) v[i] = wire[i];
    if constexpr (W % 32 != 0) v.back() &= (uint32_t(1) << (W % 32)) - 1;
    return v;
  }
}

template <int W>
void fromValue(const value_t<W>& v, std::span<uint32_t> wire) {
  if constexpr (W <= 32) {
    wire[0] = uint32_t(v);
  } else if constexpr (W <= 64) {
    wire[0] = uint32_t(v);
    wire[1] = uint32_t(v >> 32);
  } else {
    for (size_t i = 0; i < v.size(); ++i) wire[i] = v[i];
  }
}

// A value's wire image, without a copy where it already is one.
template <int W>
std::span<const uint32_t> wireOf(const value_t<W>& v) {
  if constexpr (W > 64) {
    return v;
  } else {
    static_assert(W > 64, "wireOf reads the wide values (W > 64) in place");
    return {};
  }
}

}  // namespace lancer::sc
