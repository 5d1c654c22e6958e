#pragma once

#include <memory>
#include <string>
#include <vector>

#include "driver/traversal_device.h"
#include "driver/isect_device.h"

namespace lancer {

// Every model of the intersection pipeline, by the name the CLI uses:
// golden, systemc (cycle model), rtl (Verilated, C++), rtl-systemc (Verilated, in SystemC).
std::vector<std::string> isectDeviceNames();
// Throws InputError for an unknown name.
std::unique_ptr<IsectDevice> makeIsectDevice(const std::string& name);

// Every model of the grid unit (traversal + memory + intersection pipeline).
std::vector<std::string> gridDeviceNames();
std::unique_ptr<GridDevice> makeGridDevice(const std::string& name);

// Every model of the octree unit.
std::vector<std::string> octreeDeviceNames();
std::unique_ptr<OctreeDevice> makeOctreeDevice(const std::string& name);

}  // namespace lancer
