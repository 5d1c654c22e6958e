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
//   kGroup                           nodes per node-port response (the octree's child group: 8)
//   nodes(image)                     the node table
//   nodeValues(node)                 a node's field values, in kNodeFields order
//   configValues(image)              the configuration port's field values of a run
//   build(triangles, options)        the image the driver builds for a scene
//   checkImage(image, rays)          InputError for an image or ray the unit cannot take
//   traverse(image, ray)             the golden walk
//   NodeReads(image)(trace)          node-port reads the hardware issues for a golden trace
//   imageCounters(image)             the image's figures for the summary and the report

#include <array>
#include <cstdint>
#include <span>
#include <tuple>
#include <utility>
#include <string_view>
#include <vector>

#include "golden/records.h"

namespace lancer::fx {

// The hardware paths of `lancer run --accel`: the host's BVH feeding the
// intersection pipeline, and each traversal unit.
enum class UnitKind { Isect, Grid, Octree };

// How each layer names a unit.
struct UnitNames {
  const char* unit;         // "grid": --accel, report keys, messages
  const char* module;       // "rt_grid": its RTL top and SystemC model
  const char* elements;     // what a visit enters, plural: "cells", "nodes"
  const char* nodePort;     // the RTL's prefix of the node memory port: "cell" (cell_req_valid_o)
  const char* nodeRead;     // one read of that port: "cell", "child group"
  const char* nodeTable;    // the region it reads: "cell table", "node table"
  const char* cfgPort;      // its configuration port besides cfg_slots_i: "cfg_res_i"
  const char* slotsOption;  // the CMake variable of its ray slots
  const char* rtlSources;   // the CMake variable of its RTL sources
  const char* stepsKey;     // report key and summary label of the steps ("voxel_steps", "voxel steps")
  const char* stepsLabel;
  const char* readsKey;     // ... and of the node-port reads ("cell_reads", "cell table reads")
  const char* readsLabel;
};

// A figure of a unit's memory image (the grid's resolution, the octree's depth).
struct ImageCounter {
  const char* key;    // JSON key
  const char* label;  // summary label
  double value;
};

// Where each flattened field value of a record sits (lsb, width), at compile
// time: the layout of records.h (first field most significant, element 0 of an
// array least significant), for the per-node packing below, which runs over
// every node of an image before each run.
template <const auto& Fields>
inline constexpr auto kFieldSlots = [] {
  std::array<std::pair<int, int>, valueCount(Fields)> slots{};
  int msb = recordBits(Fields);
  size_t at = 0;
  for (const FieldSpec& f : Fields) {
    msb -= f.width * f.count;
    for (int e = 0; e < f.count; ++e) slots[at++] = {msb + e * f.width, f.width};
  }
  return slots;
}();

// Ors `values` into a zeroed `wire` at the slots of `Fields`.
template <const auto& Fields, class Values>
void packAtSlots(const Values& values, std::span<uint32_t> wire) {
  constexpr auto& slots = kFieldSlots<Fields>;
  static_assert(std::tuple_size_v<Values> == slots.size(), "one value per field element");
  for (size_t i = 0; i < slots.size(); ++i) {
    const auto [lsb, width] = slots[i];
    const u128 value = width >= 128 ? values[i] : (values[i] & ((u128(1) << width) - 1));
    for (int w = lsb / 32; w <= (lsb + width - 1) / 32; ++w) {
      const int at = 32 * w - lsb;
      wire[size_t(w)] |= uint32_t(at >= 0 ? value >> at : value << -at);
    }
  }
}

// A node as its port's wire carries it (kNodeFields; element 0 of a group least significant).
template <class U>
void packNode(const typename U::Node& node, std::span<uint32_t> wire) {
  packAtSlots<U::kNodeFieldList>(U::nodeValues(node), wire);
}

// The configuration port's value of a run, as a wire image.
template <class U>
void packConfig(const typename U::Image& image, std::span<uint32_t> wire) {
  packAtSlots<U::kCfgFieldList>(U::configValues(image), wire);
}

template <class U>
inline constexpr int kNodeBitsOf = recordBits(U::kNodeFields);
template <class U>
inline constexpr int kCfgBitsOf = recordBits(U::kCfgFields);

}  // namespace lancer::fx
