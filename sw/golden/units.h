#pragma once

// Every traversal unit, by its descriptor (golden/unit.h), in the order of
// LANCER_TRAVERSAL_UNITS (cmake/Units.cmake), whose generated golden/unit_list.h
// includes them.

#include <tuple>
#include <type_traits>
#include <vector>

#include "golden/quadric.h"
#include "golden/unit_list.h"

namespace lancer::fx {

using TraversalUnits = std::tuple<LANCER_TRAVERSAL_UNIT_DESCRIPTORS>;

// Calls fn(U{}) for each descriptor U, in TraversalUnits order.
template <class Fn>
constexpr void forEachTraversalUnit(Fn&& fn) {
  std::apply([&](auto... units) { (fn(units), ...); }, TraversalUnits{});
}

// Every record that crosses the hardware boundary: the intersection
// pipeline's, the quadric pipeline's, then each unit's (rt_pkg's typedefs, in this order).
inline const std::vector<RecordSpec>& allRecords() {
  static const std::vector<RecordSpec> all = [] {
    std::vector<RecordSpec> records(std::begin(kIsectRecords), std::end(kIsectRecords));
    records.push_back(kIsectQuadric);
    forEachTraversalUnit([&](auto unit) {
      records.insert(records.end(), decltype(unit)::kRecords.begin(), decltype(unit)::kRecords.end());
    });
    return records;
  }();
  return all;
}

// The descriptor whose memory image is `Image`.
template <class Image, class Units = TraversalUnits>
struct UnitOfImage;
template <class Image, class U, class... Rest>
struct UnitOfImage<Image, std::tuple<U, Rest...>>
    : std::conditional_t<std::is_same_v<typename U::Image, Image>, std::type_identity<U>,
                         UnitOfImage<Image, std::tuple<Rest...>>> {};
template <class Image>
using UnitFor = typename UnitOfImage<Image>::type;

}  // namespace lancer::fx
