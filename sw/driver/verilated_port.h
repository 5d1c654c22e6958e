#pragma once

// Records across the ports of a Verilated model. Verilator holds a port of up
// to 64 bits in an integer and a wider one in a VlWide<N> of 32-bit words,
// least significant first: the same order as fx::Wire, so a record crosses the
// port as a block copy.

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace lancer {

template <typename Port>
constexpr size_t portWords() {
  if constexpr (std::is_integral_v<Port>) {
    return (sizeof(Port) + 3) / 4;
  } else {
    return sizeof(Port) / sizeof(uint32_t);
  }
}

template <typename Port>
void writePort(Port& port, const uint32_t* words, size_t count) {
  if constexpr (std::is_integral_v<Port>) {
    uint64_t value = words[0];
    if (count > 1) value |= uint64_t(words[1]) << 32;
    port = Port(value);
  } else {
    std::memcpy(port.data(), words, count * sizeof(uint32_t));
  }
}

template <typename Port>
void readPort(const Port& port, uint32_t* words, size_t count) {
  if constexpr (std::is_integral_v<Port>) {
    const uint64_t value = port;
    words[0] = uint32_t(value);
    if (count > 1) words[1] = uint32_t(value >> 32);
  } else {
    std::memcpy(words, port.data(), count * sizeof(uint32_t));
  }
}

}  // namespace lancer
