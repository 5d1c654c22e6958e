#include "golden/memory_image.h"

#include <fmt/format.h>

#include "common/error.h"

namespace lancer::fx {

void checkRegionFits(std::string_view unit, std::string_view region, uint64_t entries, std::string_view remedy,
                     int addrBits) {
  const uint64_t capacity = uint64_t(1) << addrBits;
  if (entries > capacity) {
    throw InputError(fmt::format("the {}'s memory image does not fit the {}-bit address width: the {} needs {} "
                                 "entries (at most {}); {} or rebuild with a larger LANCER_MEM_ADDR_BITS",
                                 unit, addrBits, region, entries, capacity, remedy));
  }
}

}  // namespace lancer::fx
