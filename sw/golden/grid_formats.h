#pragma once

// The grid unit's formats and records (docs/grid-unit.md), as golden/formats.h
// and golden/records.h are the shared ones: gen_rt_pkg emits them into rt_pkg
// through the unit's descriptor (kPkgParams, kRecords).

#include <array>

#include "golden/records.h"

namespace lancer::fx {

// ---- Uniform grid traversal unit (docs/grid-unit.md) ---------------------------
// Resolution per axis 1..kGridResMax. The grid covers the lattice cube [0, 2^P)
// and works in per-axis scaled coordinates X = x * R (exact integers), where
// cell i spans [i * 2^P, (i+1) * 2^P): the cell of a point is X >> P, no division.
inline constexpr int kGridResMax = 256;
inline constexpr int kGridResolutionBits = 9;    // holds R = 1..256
inline constexpr int kCellIndexBits = 8;   // holds a cell coordinate 0..255
inline constexpr int kGridScaleBits = 8;   // R <= 2^8
// Scaled origin X = o * R < 2^(P+8) ................................ P+8 unsigned
inline constexpr int kGridPosBits = kPosBits + kGridScaleBits;
// Scaled direction |D| = |d| * R < 2^(D-1+8) ........................ D+8 signed
inline constexpr int kGridDirBits = kDirBits + kGridScaleBits;
// Product of the other two axes' |D|: < 2^(2(D+7)) ................ 2D+14 unsigned
inline constexpr int kGridPairBits = 2 * (kDirBits + 7);
// Product of all three |D|: < 2^(3(D+7)) ............................ 3D+21 unsigned
inline constexpr int kGridTripleBits = 3 * (kDirBits + 7);
// DDA accumulator N_a = (distance to the next boundary along a) * (product of the
// other active |D|), in the same units for all axes so comparing them compares
// the t of the next crossing. Starts <= 2^P * 2^(2D+14), grows by one cell
// (2^P * pair) per step, at most R steps: < 2^(P+8) * 2^(2D+14) ... P+2D+23 unsigned
inline constexpr int kGridAccBits = kPosBits + 2 * kDirBits + 23;
static_assert(kGridAccBits + kDirBits <= 127, "N * |d| must fit u128 for the exit test");

// ---- grid_cell_t: one entry of the grid unit's cell table -----------------------
inline constexpr FieldSpec kGridCellFields[] = {
    {"first", 32, 1, false, "first entry of the cell's run in the index list"},
    {"count", 32, 1, false, "triangles listed in the cell"},
};
// ---- grid_visit_t: one voxel step, on the unit's trace stream; grid_res_t --------
inline constexpr auto kGridVisitFields = traversalVisitFields("cell_id", 3 * kCellIndexBits, "(z * Ry + y) * Rx + x");
inline constexpr auto kGridResFields = traversalResFields("cells", "cells visited");

inline constexpr RecordSpec kGridRecords[] = {
    {"grid_cell_t", "GRID_CELL_W", "a grid cell table entry", kGridCellFields},
    {"grid_visit_t", "GRID_VISIT_W", "a grid unit voxel step", kGridVisitFields},
    {"grid_res_t", "GRID_RESULT_W", "a grid unit ray result", kGridResFields},
};
inline constexpr int kGridCellBits = recordBits(kGridCellFields);

// rt_grid_setup's register stages: a ray accepted at edge t loads its slot at
// edge t + 1 + kGridSetupLatency (one multiplication deep each: the scaled
// origin and |D|, the pairs, the accumulators). The RTL builds these stages;
// the SystemC shell model carries the ray through as many.
inline constexpr int kGridSetupLatency = 3;

// What rt_pkg holds of the grid's formats (before its records' widths) and of
// its latencies (after them).
inline constexpr PackageParam kGridFormatParams[] = {
    {"GRID_RES_MAX", kGridResMax},       {"GRID_RESOLUTION_W", kGridResolutionBits},
    {"CELL_INDEX_W", kCellIndexBits},    {"GRID_POS_W", kGridPosBits},
    {"GRID_DIR_W", kGridDirBits},        {"GRID_PAIR_W", kGridPairBits},
    {"GRID_TRIPLE_W", kGridTripleBits},  {"GRID_ACC_W", kGridAccBits},
};
inline constexpr PackageParam kGridLatencies[] = {{"GRID_SETUP_LATENCY", kGridSetupLatency}};

}  // namespace lancer::fx
