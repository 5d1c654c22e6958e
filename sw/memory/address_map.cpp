#include "memory/address_map.h"

#include <fmt/format.h>

#include "common/error.h"

namespace lancer::mem {

AddressMap::AddressMap(std::array<Region, kRegions> regions) : regions_(std::move(regions)) {
  const uint64_t limit = uint64_t(1) << kAddressBits;
  uint64_t next = kBase;
  for (Region& r : regions_) {
    r.base = next;
    // A read may run past the last record by a partial group (the octree's
    // last child group): the region reserves room for it.
    const uint64_t bytes = r.bytes() + uint64_t(r.recordsPerRead - 1) * r.recordBytes;
    if (r.base + bytes > limit) {
      throw InputError(fmt::format("the memory image does not fit the chip's {}-bit address space: the {} "
                                   "({} records of {} bytes) would end at byte {:#x}, past {:#x}",
                                   kAddressBits, r.name, r.records, r.recordBytes, r.base + bytes, limit));
    }
    next = (r.base + bytes + kPageBytes - 1) / kPageBytes * kPageBytes;
  }
  end_ = next;
}

}  // namespace lancer::mem
