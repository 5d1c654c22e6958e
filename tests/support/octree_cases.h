#pragma once

// The hard cases of the octree unit (docs/octree-unit.md) as reusable stimulus:
// each a memory image and the quantized rays to walk through it, shared by the
// test programs of every model of the unit (the Verilated RTL in
// tests/rtl/octree/, the SystemC model in tests/sc/), which compare each model
// against fx::traverseOctree bit for bit.
//
//   axis_parallel       rays along each axis, both signs, +0/-0 in the others,
//                       off and on the mid-planes of the root and of deeper nodes
//   mid_planes          rays lying in a mid-plane (one zero component), random otherwise
//   centre_and_corners  through the root's centre along every diagonal; from node
//                       corners through other corners (exact ties on every
//                       axis) and along node edges, at depths 1..8
//   octants             all eight direction octants from several origins
//   node_faces          origins exactly on node faces at every depth
//   root_faces          origins on the root's faces, corners and edges, rays
//                       leaving through a face at t = 0 and rays that miss the root
//   deep_leaf_origins   origins inside leaves one or two lattice units wide
//   off_centre_low/high the scene in a corner of the lattice, every axis mirrored
//   max_depth           OCTREE_MAX_DEPTH with tiny nodes (leaves one unit wide)
//   deep_sparse         one small triangle in a corner: long walks through empty nodes
//   full                the Cornell box subdivided, split as deep as it goes
//   empty_leaves        a few small triangles far apart: mostly empty leaves
//   crowded_leaf        leaves with hundreds of triangles
//   root_leaf, empty    the root a leaf (few triangles), and no triangles at all
//   tiny_components     direction components of +-1: huge parameters
//   cornell_random      the built-in Cornell box through lancer::Quantizer, random
//                       float rays through the quantizer and random lattice rays
//
// Every ray has a non-zero direction (the quantizer guarantees one) and ids
// 0..n-1 within its case. Building all cases takes well under a second.

#include <cstdint>
#include <string>
#include <vector>

#include "driver/traversal_device.h"
#include "golden/octree.h"
#include "scene/scene.h"
#include "support/traversal_cases.h"

namespace lancer::test {

using OctreeCase = TraversalCase<fx::OctreeImage>;

// All the cases above, in that order (names unique).
std::vector<OctreeCase> octreeHardCases();

// (Scenes through the quantizer, QuantizedScene and quantizedCamera, come from
// support/traversal_cases.h.)

}  // namespace lancer::test
