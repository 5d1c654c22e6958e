#pragma once

// Each traversal unit's SystemC and Verilated devices by their types, for the
// tests that need more than the model table's TraversalDevice: port traces,
// the mixed model, several devices alive at once. One line per unit and model.

#include "driver/systemc_traversal_device.h"
#include "driver/verilator_traversal_device.h"
#include "bvh/rt_bvh_unit.h"
#include "grid/rt_grid_unit.h"
#include "octree/rt_octree_unit.h"

class Vrt_grid;
class Vrt_octree;
class Vrt_bvh;

namespace lancer {

// "systemc" (rt_grid_model), "rtl-systemc" (Vrt_grid_sc) and the mixed
// Impl::ModelRtlIsect (rt_grid_model with the Verilated rt_isect inside).
using SystemCGridDevice = SystemCTraversalDevice<fx::GridImage, sc::rt_grid_unit>;
// rt_grid with its rt_isect: node reads may run up to CellQueue - 1 cells past
// a ray's last cell (prefetch).
using VerilatorGridDevice = VerilatorTraversalDevice<Vrt_grid, fx::GridImage>;

// "systemc" (rt_octree_model) and "rtl-systemc" (Vrt_octree_sc); no mixed
// implementation (Impl::ModelRtlIsect throws: rt_octree_model holds no rt_isect).
using SystemCOctreeDevice = SystemCTraversalDevice<fx::OctreeImage, sc::rt_octree_unit>;
// rt_octree with its rt_isect: a node request at `first` returns the child group first .. first+7.
using VerilatorOctreeDevice = VerilatorTraversalDevice<Vrt_octree, fx::OctreeImage>;

// "systemc" (rt_bvh_model) and "rtl-systemc" (Vrt_bvh_sc); no mixed implementation.
using SystemCBvhDevice = SystemCTraversalDevice<fx::BvhImage, sc::rt_bvh_unit>;
// rt_bvh with its rt_isect: a node request at `addr` returns node addr (both children's boxes).
using VerilatorBvhDevice = VerilatorTraversalDevice<Vrt_bvh, fx::BvhImage>;

}  // namespace lancer
