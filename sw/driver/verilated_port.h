#pragma once

// Records across the ports of a clocked model. Verilator holds a port of up
// to 64 bits in an integer and a wider one in a VlWide<N> of 32-bit words,
// least significant first: the same order as fx::Wire, so a record crosses the
// port as a block copy. The SystemC cycle models' value ports (rt_value,
// systemc/base/rt_value.h) hold the same types in their `value`.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>

namespace lancer {

// What a port holds: the port itself (Verilator), or its value (rt_value).
template <typename Port>
constexpr auto& portValue(Port& port) {
  if constexpr (requires { port.value; }) {
    return port.value;
  } else {
    return port;
  }
}

template <typename Port>
using PortValue = std::remove_cvref_t<decltype(portValue(std::declval<Port&>()))>;

template <typename Port>
constexpr size_t portWords() {
  using V = PortValue<Port>;
  if constexpr (std::is_integral_v<V>) {
    return (sizeof(V) + 3) / 4;
  } else {
    return sizeof(V) / sizeof(uint32_t);
  }
}

template <typename Port>
void writePort(Port& port, const uint32_t* words, size_t count) {
  auto& v = portValue(port);
  using V = PortValue<Port>;
  if constexpr (std::is_integral_v<V>) {
    uint64_t value = words[0];
    if (count > 1) value |= uint64_t(words[1]) << 32;
    v = V(value);
  } else {
    std::memcpy(v.data(), words, count * sizeof(uint32_t));
  }
}

template <typename Port>
void readPort(const Port& port, uint32_t* words, size_t count) {
  const auto& v = portValue(port);
  if constexpr (std::is_integral_v<PortValue<const Port>>) {
    const uint64_t value = v;
    words[0] = uint32_t(value);
    if (count > 1) words[1] = uint32_t(value >> 32);
  } else {
    std::memcpy(words, v.data(), count * sizeof(uint32_t));
  }
}

}  // namespace lancer
