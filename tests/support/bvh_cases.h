#pragma once

// The hard cases of the BVH unit (docs/bvh-unit.md) as reusable stimulus:
// each a memory image and the quantized rays to walk through it, shared by the
// test programs of every model of the unit (the Verilated RTL in
// tests/rtl/bvh/, the SystemC model in tests/sc/), which compare each model
// against fx::traverseBvh bit for bit.
//
//   axis_parallel       rays along each axis, both signs, from the planes of
//                       the image's child boxes and between them
//   box_corners         from the corners of child boxes through other corners
//                       (diagonals: exact ties of the entry parameters on
//                       every axis) and along their edges
//   box_faces           origins exactly on child boxes' faces: rays lying in
//                       the face, leaving through it at t = 0, entering through it
//   octants             all eight direction octants from several origins
//   crowded_leaf        a leaf of 255 triangles (BVH_COUNT_W's limit), all
//                       with one box: ties of the closest hit by id
//   root_leaf, empty    the root a leaf (few triangles), and no triangles at all
//   chain               an image of kBvhMaxLevels levels whose walk fills the
//                       stack (BVH_STACK_DEPTH entries), the deepest allowed
//   tiny_components     direction components of +-1: huge parameters
//   cornell_random      the built-in Cornell box through lancer::Quantizer,
//                       random and aimed lattice rays
//   cornell_segments    the same scene with segment ends and any-hit rays
//                       (segmentVariants): the cull rule before the first hit,
//                       an any-hit ray ending after the leaf of its hit
//
// Every ray has a non-zero direction (the quantizer guarantees one) and ids
// 0..n-1 within its case.

#include <cstdint>
#include <string>
#include <vector>

#include "driver/traversal_device.h"
#include "golden/bvh.h"
#include "support/traversal_cases.h"

namespace lancer::test {

using BvhCase = TraversalCase<fx::BvhImage>;

// All the cases above, in that order (names unique).
std::vector<BvhCase> bvhHardCases();

// A chain of `levels` levels: each interior node's child 0 is the next interior
// node (the last one's a leaf), child 1 a leaf; both children's boxes are the
// whole lattice, so a ray enters both at every level, takes child 0 (equal
// entries) and pushes child 1: a walk of `levels` levels pushes levels - 1
// entries. kBvhMaxLevels fills the stack; one more is refused by checkImage,
// and overflows the stack if it slips past (the RTL's a_stack_depth).
fx::BvhImage bvhChainImage(int levels);
// A root whose two children are empty leaves spanning the lattice.
fx::BvhImage bvhTwoEmptyLeaves();

}  // namespace lancer::test
