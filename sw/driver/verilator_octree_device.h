#pragma once

// VerilatorTraversalDevice for rt_octree: declared with the other units in
// verilator_traversal_device.h, its traits in verilator_octree_device.cpp.
#include "driver/verilator_traversal_device.h"
