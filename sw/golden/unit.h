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
//                                    (all eight from UnitRecords, below)
//   kGroup                           nodes per node-port response (the octree's child group: 8)
//   kSetupLatency                    the per-ray setup's register stages (rt_<unit>_setup)
//   nodes(image)                     the node table
//   nodeValues(node)                 a node's field values, in kNodeFields order
//   configValues(image)              the configuration port's field values of a run
//   build(triangles, options)        the image the driver builds for a scene
//   checkImage(image, rays)          InputError for an image or ray the unit cannot take
//   traverse(image, ray)             the golden walk
//   NodeReads(image)(trace)          node-port reads the hardware issues for a golden trace
//   imageCounters(image)             the image's figures for the summary and the report

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "golden/record_bits.h"
#include "golden/records.h"

namespace lancer::fx {

// The hardware paths of `lancer run --accel`: the host's BVH feeding the
// intersection pipeline, and each traversal unit.
enum class UnitKind { Isect, Grid, Octree, Bvh };

// A descriptor's records, from its lists (golden/<unit>_formats.h): derive
// from UnitRecords<node fields, configuration fields, visit fields, result
// fields, records, package parameters> and the members above come with it.
template <const auto& NodeFields, const auto& CfgFields, const auto& VisitFields, const auto& ResFields,
          const auto& Records, const auto& PkgParams>
struct UnitRecords {
  static constexpr const auto& kNodeFieldList = NodeFields;
  static constexpr const auto& kCfgFieldList = CfgFields;
  static constexpr std::span<const FieldSpec> kNodeFields = NodeFields;
  static constexpr std::span<const FieldSpec> kVisitFields = VisitFields;
  static constexpr std::span<const FieldSpec> kResFields = ResFields;
  static constexpr std::span<const FieldSpec> kCfgFields = CfgFields;
  static constexpr std::span<const RecordSpec> kRecords = Records;
  static constexpr std::span<const PackageParam> kPkgParams = PkgParams;
};

// How each layer names a unit.
struct UnitNames {
  const char* unit;         // "grid": --accel, report keys, messages
  const char* module;       // "rt_grid": its RTL top and SystemC model
  const char* elements;     // what a visit enters, plural: "cells", "nodes"
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

}  // namespace lancer::fx
