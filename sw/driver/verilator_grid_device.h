#pragma once

// VerilatorTraversalDevice for rt_grid: declared with the other units in
// verilator_traversal_device.h, its traits in verilator_grid_device.cpp.
#include "driver/verilator_traversal_device.h"
