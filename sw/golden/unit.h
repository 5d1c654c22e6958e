#pragma once

// What every layer needs to know of a traversal unit, in one place: its
// names, its records, its configuration, how its node port packs the memory
// image, how the driver builds and checks that image, the golden walk, and its
// image's figures for the report. Each unit has one descriptor beside its
// golden model (golden/grid_unit.h, golden/octree_unit.h), listed once in
// golden/units.h; the SystemC traits, the Verilated traits, the job, the model
// table and the CLI's --accel choices derive from it.
//
// A descriptor `U` provides:
//   Image, Node                      the memory image and one entry of its node table
//   kKind, kNames                    its hardware path and names (UnitNames)
//   kNodeFields, kVisitFields,       its records (golden/<unit>_formats.h); the node
//   kResFields, kCfgFields           and configuration lists also as the arrays
//   kNodeFieldList, kCfgFieldList    themselves, for the compile-time packing
//   kRecords, kPkgParams             what rt_pkg holds of its records and formats
//                                    (Image, Node, kKind and these eight from UnitBase, below)
//   kGroup                           nodes per node-port response (the octree's child group: 8)
//   kSetupLatency                    the per-ray setup's register stages (rt_<unit>_setup)
//   nodes(image)                     the node table
//   nodeValues(node)                 a node's field values, in kNodeFields order
//   configValues(image)              the configuration port's field values of a run
//   buildOptions()                   the options of `lancer run` that build reads (BuildOption)
//   build(triangles, options, quadrics)  the image the driver builds for a scene
//   checkImage(image, rays)          InputError for an image or ray the unit cannot take
//   traverse(image, ray)             the golden walk
//   NodeReads(image)(trace)          node-port reads the hardware issues for a golden trace
//   imageCounters(image)             the image's figures for the summary and the report

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

// What a descriptor's build and checkImage take and throw.
#include <fmt/format.h>

#include "common/accel_options.h"
#include "common/error.h"
#include "golden/record_bits.h"
#include "golden/records.h"
#include "golden/unit_kinds.h"  // generated from LANCER_TRAVERSAL_UNITS (cmake/Units.cmake)

namespace lancer::fx {

// The hardware paths of `lancer run --accel`: the host's BVH feeding the
// intersection pipeline, and each traversal unit (Grid, Octree, Bvh: the
// kinds of LANCER_TRAVERSAL_UNITS).
enum class UnitKind { Isect, LANCER_TRAVERSAL_UNIT_KINDS };

// A descriptor's kind, types and records, from its lists
// (golden/<unit>_formats.h): derive from UnitBase<kind, image, node, node
// fields, configuration fields, records, format parameters, latencies> and
// Image, Node, kKind and the record members above come with it. The records are
// the unit's own (node, reference), then its visit and its result record;
// kPkgParams holds, in this order, its format parameters, its records' widths
// (RecordSpec::widthParam) and its latencies.
template <UnitKind Kind, class ImageT, class NodeT, const auto& NodeFields, const auto& CfgFields,
          const auto& Records, const auto& FormatParams, const auto& Latencies>
struct UnitBase {
  using Image = ImageT;
  using Node = NodeT;
  static constexpr UnitKind kKind = Kind;
  static constexpr const auto& kNodeFieldList = NodeFields;
  static constexpr const auto& kCfgFieldList = CfgFields;
  static constexpr std::span<const FieldSpec> kNodeFields = NodeFields;
  static constexpr std::span<const FieldSpec> kVisitFields = Records[std::size(Records) - 2].fields;
  static constexpr std::span<const FieldSpec> kResFields = Records[std::size(Records) - 1].fields;
  // The result record's fields as an array, for the compile-time packing (wire_bits::packFixed, unpackFixed).
  static constexpr auto kResFieldList = [] {
    std::array<FieldSpec, Records[std::size(Records) - 1].fields.size()> fields{};
    std::copy(kResFields.begin(), kResFields.end(), fields.begin());
    return fields;
  }();
  static constexpr std::span<const FieldSpec> kCfgFields = CfgFields;
  static constexpr std::span<const RecordSpec> kRecords = Records;
  static constexpr auto kPkgParamList = [] {
    std::array<PackageParam, std::size(FormatParams) + std::size(Records) + std::size(Latencies)> params{};
    auto out = std::copy(std::begin(FormatParams), std::end(FormatParams), params.begin());
    out = std::transform(std::begin(Records), std::end(Records), out, widthParam);
    std::copy(std::begin(Latencies), std::end(Latencies), out);
    return params;
  }();
  static constexpr std::span<const PackageParam> kPkgParams = kPkgParamList;
};

// How a unit's descriptor names what it visits and counts (a descriptor lists
// them in this order).
struct UnitWords {
  const char* elements;    // what a visit enters, plural: "cells", "nodes"
  const char* nodeRead;    // one read of its node port: "cell", "child group"
  const char* nodeTable;   // the region it reads: "cell table", "node table"
  const char* cfgPort;     // its configuration port besides cfg_slots_i: "cfg_res_i"
  const char* stepsKey;    // report key and summary label of the steps ("voxel_steps", "voxel steps")
  const char* stepsLabel;
  const char* readsKey;    // ... and of the node-port reads ("cell_reads", "cell table reads")
  const char* readsLabel;
};

// How each layer names a unit: its words, and the names that follow from its
// own (unitNames<"grid">).
struct UnitNames : UnitWords {
  const char* unit;         // "grid": --accel, report keys, messages
  const char* module;       // "rt_grid": its RTL top and SystemC model
  const char* slotsOption;  // the CMake variable of its ray slots: "LANCER_GRID_RAYS_IN_FLIGHT"
  const char* rtlSources;   // the CMake variable of its RTL sources: "LANCER_RTL_GRID_SOURCES"
};

// A name as a template argument, NUL-terminated, joined and upper-cased at
// compile time (the text of a static member stays put: a const char*).
template <size_t N>
struct FixedName {
  char text[N]{};
  constexpr FixedName() = default;
  constexpr FixedName(const char (&s)[N]) { std::copy_n(s, N, text); }
};
template <size_t A, size_t B>
constexpr FixedName<A + B - 1> operator+(const FixedName<A>& a, const FixedName<B>& b) {
  FixedName<A + B - 1> joined;
  std::copy_n(a.text, A - 1, joined.text);
  std::copy_n(b.text, B, joined.text + A - 1);
  return joined;
}
template <size_t N>
constexpr FixedName<N> upperCase(FixedName<N> name) {
  for (char& c : name.text) c = (c >= 'a' && c <= 'z') ? char(c - 'a' + 'A') : c;
  return name;
}

template <FixedName Unit>
struct DerivedUnitNames {
  static constexpr auto kUnit = Unit;
  static constexpr auto kModule = FixedName("rt_") + Unit;
  static constexpr auto kSlotsOption = FixedName("LANCER_") + upperCase(Unit) + FixedName("_RAYS_IN_FLIGHT");
  static constexpr auto kRtlSources = FixedName("LANCER_RTL_") + upperCase(Unit) + FixedName("_SOURCES");
};

template <FixedName Unit>
constexpr UnitNames unitNames(const UnitWords& words) {
  using Derived = DerivedUnitNames<Unit>;
  return {words, Derived::kUnit.text, Derived::kModule.text, Derived::kSlotsOption.text, Derived::kRtlSources.text};
}

// A build option of a unit's image (--bvh-leaf): how `lancer run` takes it,
// the AccelOptions field it sets, and the image counters that report the value
// the image was built with. A replay's command line repeats it where it differs
// from AccelOptions' default; the sweep's reference trace passes the reported
// value to `lancer trace` (the float structure takes the same flag) when the
// counters agree, for the options that shape the tree (not the ones that only
// lay it out in memory). The CLI refuses a value outside the rule (positive)
// and `max` before anything runs; tests/cli/build_options_test.cpp tries both
// bounds of every option.
struct BuildOption {
  const char* flag;
  int AccelOptions::*field;
  std::string help;                     // in `lancer run --help`
  bool positive;                        // refused unless > 0 (else unless >= 0)
  std::vector<const char*> reportKeys;  // "bvh_leaf_size"; the grid's three axes
  bool shapesReference = true;          // the float structure takes it too (`lancer trace`); not a layout's
  int max = std::numeric_limits<int>::max();  // the largest value the unit takes (this default: no limit)
};

// A walk set aside by the treelet schedule, as a ray queue sees it: the block
// it waits for and the bits its queue entry holds (the ray and its walk record).
struct WaitingWalk {
  uint32_t block;
  int bits;
};

// The block of a treelet layout for a budget of `bytes` (`flag`,
// --<unit>-treelet-bytes): the most node-table entries of `nodeBytes` each, a
// power of two, that fit it. A budget below the smallest block (`leastNodes`
// entries: one `least`) is an error naming the flag.
inline uint32_t treeletBlockNodes(const char* flag, int bytes, uint32_t nodeBytes, uint32_t leastNodes,
                                  const char* least) {
  if (bytes < int(nodeBytes * leastNodes)) {
    throw InputError(
        fmt::format("{} {}: a treelet holds at least one {} ({} bytes)", flag, bytes, least, nodeBytes * leastNodes));
  }
  return std::bit_floor(uint32_t(bytes) / nodeBytes);
}
// An image's treelet layout (treeletNodes: its blocks' entries, 0 without
// one): whether it has one, and its blocks' shift (cfg_block_shift_i).
template <class Image>
bool hasTreeletLayout(const Image& image) {
  return image.treeletNodes != 0;
}
template <class Image>
uint32_t treeletBlockShift(const Image& image) {
  return image.treeletNodes ? uint32_t(std::countr_zero(image.treeletNodes)) : 0;
}

// A figure of a unit's memory image (the grid's resolution, the octree's depth).
struct ImageCounter {
  const char* key;    // JSON key
  const char* label;  // summary label
  double value;
};

// A node as its port's wire carries it (kNodeFields, at compile-time positions:
// the packing runs over every node of an image before each run).
template <class U>
void packNode(const typename U::Node& node, std::span<uint32_t> wire) {
  wire_bits::packFixed<U::kNodeFieldList>(U::nodeValues(node), wire);
}

// The configuration port's value of a run, as a wire image.
template <class U>
void packConfig(const typename U::Image& image, std::span<uint32_t> wire) {
  wire_bits::packFixed<U::kCfgFieldList>(U::configValues(image), wire);
}

template <class U>
inline constexpr int kNodeBitsOf = recordBits(U::kNodeFields);
template <class U>
inline constexpr int kCfgBitsOf = recordBits(U::kCfgFields);

// A unit that can set walks aside (the treelet schedule, docs/scheduling.md):
// its descriptor has a walk record (kWalkFieldList, kBlockShiftBits),
// kTreeletFlag, suspended and treeletCrossings, its image a treelet layout
// (treeletNodes: hasTreeletLayout, treeletBlockShift).
template <class U>
concept SuspendsWalks = requires { U::kWalkFieldList; };
// Its walk record's bits (0 for a unit that cannot set walks aside).
template <class U>
inline constexpr int kWalkBitsOf = [] {
  if constexpr (SuspendsWalks<U>) {
    return recordBits(U::kWalkFieldList);
  } else {
    return 0;
  }
}();

}  // namespace lancer::fx
