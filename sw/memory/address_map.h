#pragma once

// Where a unit's memory image lies in the chip's address space: its four
// regions (node table, index list, triangle table, quadric table) one after
// the other from kBase, each aligned to a page, each record at the byte size the RTL reads
// (a node: its record's bits rounded up to bytes; a node-port read fetches
// the descriptor's kGroup nodes at once). Every unit of a chip reads the same
// image, so the L2 and DRAM see one copy.

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>

#include "golden/formats.h"
#include "memory/config.h"

namespace lancer::mem {

struct Region {
  std::string name;           // "cell table", "index list", "triangle table"
  uint64_t base = 0;          // byte address of record 0
  uint32_t recordBytes = 1;   // bytes of one record
  uint32_t recordsPerRead = 1;  // records one request returns (the octree's child group: 8)
  uint64_t records = 0;

  uint64_t bytes() const { return records * recordBytes; }
};

// The byte range of one read: [first, first + bytes).
struct ReadSpan {
  uint64_t first = 0;
  uint32_t bytes = 0;
};

// The regions of an image: one a port, and the quadric table, which the
// triangle port reads too (a primitive read: an index entry, whose kind bit
// fx::kQuadricEntryBit selects the table).
inline constexpr int kRegions = kPorts + 1;
inline constexpr size_t kQuadricRegion = size_t(kPorts);

class AddressMap {
 public:
  static constexpr int kAddressBits = 32;            // the chip's physical byte addresses
  static constexpr uint64_t kBase = 0x8000'0000;     // the DRAM window's start, as on most SoCs
  static constexpr uint64_t kPageBytes = 4096;

  AddressMap() = default;
  // The regions in port order, then the quadric table; throws InputError if
  // the image does not fit below 2^kAddressBits (naming the region and the
  // sizes).
  explicit AddressMap(std::array<Region, kRegions> regions);

  const Region& region(Port port) const { return regions_[size_t(port)]; }
  const Region& quadricRegion() const { return regions_[kQuadricRegion]; }
  // The bytes read by a request for `record` on `port` (on the triangle port,
  // an index entry: a triangle's place, or a quadric's with its kind bit).
  ReadSpan span(Port port, uint32_t record) const {
    const bool quadric = port == Port::Triangle && (record & fx::kQuadricEntryBit) != 0;
    const Region& r = regions_[quadric ? kQuadricRegion : size_t(port)];
    return {r.base + uint64_t(record & ~(quadric ? fx::kQuadricEntryBit : 0u)) * r.recordBytes,
            r.recordBytes * r.recordsPerRead};
  }
  // The most bytes one read on `port` may take.
  uint32_t maxReadBytes(Port port) const {
    const uint32_t bytes = span(port, 0).bytes;
    return port == Port::Triangle ? std::max(bytes, span(port, fx::kQuadricEntryBit).bytes) : bytes;
  }
  uint64_t end() const { return end_; }  // one past the last byte of the image
  uint64_t imageBytes() const { return end_ - kBase; }

 private:
  std::array<Region, kRegions> regions_{};
  uint64_t end_ = kBase;
};

}  // namespace lancer::mem
