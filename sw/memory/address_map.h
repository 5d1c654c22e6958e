#pragma once

// Where a unit's memory image lies in the chip's address space: its three
// regions (node table, index list, triangle table) one after the other from
// kBase, each aligned to a page, each record at the byte size the RTL reads
// (a node: its record's bits rounded up to bytes; a node-port read fetches
// the descriptor's kGroup nodes at once). Every unit of a chip reads the same
// image, so the L2 and DRAM see one copy.

#include <array>
#include <cstdint>
#include <string>

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

class AddressMap {
 public:
  static constexpr int kAddressBits = 32;            // the chip's physical byte addresses
  static constexpr uint64_t kBase = 0x8000'0000;     // the DRAM window's start, as on most SoCs
  static constexpr uint64_t kPageBytes = 4096;

  AddressMap() = default;
  // The regions in port order; throws InputError if the image does not fit
  // below 2^kAddressBits (naming the region and the sizes).
  explicit AddressMap(std::array<Region, kPorts> regions);

  const Region& region(Port port) const { return regions_[size_t(port)]; }
  // The bytes read by a request for `record` on `port`.
  ReadSpan span(Port port, uint32_t record) const {
    const Region& r = regions_[size_t(port)];
    return {r.base + uint64_t(record) * r.recordBytes, r.recordBytes * r.recordsPerRead};
  }
  uint64_t end() const { return end_; }  // one past the last byte of the image
  uint64_t imageBytes() const { return end_ - kBase; }

 private:
  std::array<Region, kPorts> regions_{};
  uint64_t end_ = kBase;
};

}  // namespace lancer::mem
