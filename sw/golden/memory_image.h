#pragma once

#include <cstdint>
#include <string_view>

#include "golden/formats.h"

namespace lancer::fx {

// Throws InputError unless a region of a unit's memory image (`entries`
// records) is addressable with `addrBits` bits. `unit` names the structure
// ("grid", "octree"), `remedy` what the user can change.
void checkRegionFits(std::string_view unit, std::string_view region, uint64_t entries, std::string_view remedy,
                     int addrBits = kMemAddrBits);

}  // namespace lancer::fx
