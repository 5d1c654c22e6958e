#pragma once

// The port types of rt_isect as SystemC sees them, shared by the hand-written
// cycle model (rt_isect_model), the Verilated RTL (Vrt_isect_sc) and the
// testbench, so that either implementation drops into the same sockets.
//
// Verilator 5.006 --sc (no --pins-* options) maps a W-bit port to
//     W == 1        bool
//     2 <= W <= 32  uint32_t
//     33 <= W <= 64 uint64_t
//     W > 64        sc_bv<W>
// (checked on a probe module with 1-, 8-, 32-, 40-, 64-, 65- and 100-bit ports).
// The record widths follow LANCER_POS_BITS / LANCER_DIR_BITS, so which branch a
// port takes is decided here at compile time: with the narrowest formats the
// ray (56 bits) is a uint64_t, by default every record is an sc_bv.
//
// Bit layout: a port value holds the record's wire image (sw/golden/records.h):
// bit i of the port is bit i%32 of word i/32, words least significant first.

#include <cstdint>
#include <span>
#include <type_traits>

#include <systemc>

#include "base/rt_value.h"
#include "golden/quadric.h"
#include "golden/records.h"

namespace lancer::sc {

template <int W>
using vl_port_t =
    std::conditional_t<(W == 1), bool,
                       std::conditional_t<(W <= 32), uint32_t,
                                          std::conditional_t<(W <= 64), uint64_t, sc_dt::sc_bv<W>>>>;

// rt_pkg's record widths, under rt_pkg's names.
inline constexpr int ISECT_RAY_W = fx::kIsectRayBits;
inline constexpr int ISECT_TRI_W = fx::kIsectTriBits;
inline constexpr int ISECT_RES_W = fx::kIsectResBits;
inline constexpr int ISECT_LATENCY = fx::kIsectLatency;
inline constexpr int ISECT_QUADRIC_W = fx::kIsectQuadricBits;
inline constexpr int QUADRIC_LATENCY = fx::kQuadricLatency;

// The types Verilator gives req_ray_i, req_tri_i and res_data_o.
using isect_ray_t = vl_port_t<ISECT_RAY_W>;
using isect_tri_t = vl_port_t<ISECT_TRI_W>;
using isect_res_t = vl_port_t<ISECT_RES_W>;

// Wire image (fx::wireWords(W) words) -> port value. Bits above W are dropped.
template <int W>
vl_port_t<W> toPort(std::span<const uint32_t> wire) {
  if constexpr (W <= 64) {
    return toValue<W>(wire);  // the same type (base/rt_value.h)
  } else {
    sc_dt::sc_bv<W> value;
    for (int i = 0; i < fx::wireWords(W); ++i) value.set_word(i, wire[size_t(i)]);
    value.clean_tail();
    return value;
  }
}

// Port value -> wire image, into the first fx::wireWords(W) words of `wire`
// (allocates nothing; the devices use this form on every cycle).
template <int W>
void fromPort(const vl_port_t<W>& value, std::span<uint32_t> wire) {
  if constexpr (W <= 64) {
    fromValue<W>(value, wire);
  } else {
    for (int i = 0; i < fx::wireWords(W); ++i) wire[size_t(i)] = value.get_word(i);
  }
}

// Port value -> wire image of fx::wireWords(W) words.
template <int W>
fx::Wire fromPort(const vl_port_t<W>& value) {
  fx::Wire wire(size_t(fx::wireWords(W)), 0);
  fromPort<W>(value, wire);
  return wire;
}

// A port value as Verilator's --sc types hold it <-> the value a cycle model
// holds (base/rt_value.h): what a pin-level module copies at its ports.
template <int W>
void pinToValue(const vl_port_t<W>& pin, value_t<W>& v) {
  if constexpr (W <= 64) {
    v = pin;
  } else {
    fromPort<W>(pin, v);
  }
}

template <int W>
vl_port_t<W> pinOf(const value_t<W>& v) {
  if constexpr (W <= 64) {
    return v;
  } else {
    return toPort<W>(v);
  }
}

// A value port's wire image: in place for the wide records, else through
// `scratch` (at least fx::wireWords(W) words).
template <int W>
std::span<const uint32_t> wireIn(const value_t<W>& v, std::span<uint32_t> scratch) {
  if constexpr (W > 64) {
    return wireOf<W>(v);
  } else {
    fromValue<W>(v, scratch);
    return scratch;
  }
}

// A result into a value port: in place for the wide records.
template <int W>
void packInto(const fx::IsectResult& result, value_t<W>& out) {
  if constexpr (W > 64) {
    fx::packWire(result, out);  // packing clears the bits above the record
  } else {
    fx::ResWire wire{};
    fx::packWire(result, wire);
    out = toValue<W>(wire);
  }
}

}  // namespace lancer::sc
