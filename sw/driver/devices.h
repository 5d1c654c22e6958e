#pragma once

#include <memory>
#include <string>
#include <vector>

#include "driver/hardware_devices.h"
#include "driver/isect_device.h"
#include "driver/traversal_device.h"

namespace lancer {

// Every model of the intersection pipeline, by the name the CLI uses:
// golden, systemc (cycle model), rtl (Verilated, C++), rtl-systemc (Verilated, in SystemC).
std::vector<std::string> isectDeviceNames();
// Throws InputError for an unknown name.
std::unique_ptr<IsectDevice> makeIsectDevice(const std::string& name);

// Every model of the traversal unit `Unit` (its descriptor; traversal +
// memory + intersection pipeline), by the same names. Instantiated for every
// unit of fx::TraversalUnits.
template <class Unit>
std::vector<std::string> traversalDeviceNames();
// Throws InputError for an unknown name.
template <class Unit>
std::unique_ptr<DeviceOf<Unit>> makeTraversalDevice(const std::string& name);

}  // namespace lancer
