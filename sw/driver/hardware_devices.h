#pragma once

// Each traversal unit's hardware models, defined by the unit's own driver
// files (systemc_<unit>_device.cpp, verilator_<unit>_device.cpp) for its
// descriptor `Unit` (golden/unit.h). The model table (devices.cpp) reaches
// every unit through these, so it names none.

#include <memory>

#include "driver/traversal_device.h"

namespace lancer {

// The implementations of a SystemC traversal device (systemc_traversal_device.h).
enum class SystemCImpl { Model, Pins, Rtl, ModelRtlIsect };

template <class Unit>
using DeviceOf = TraversalDevice<typename Unit::Image>;

template <class Unit>
std::unique_ptr<DeviceOf<Unit>> makeSystemCDevice(SystemCImpl impl);
// Whether this build has the unit's RTL Verilated for SystemC ("rtl-systemc").
template <class Unit>
bool systemCRtlAvailable();
template <class Unit>
std::unique_ptr<DeviceOf<Unit>> makeVerilatorDevice();

}  // namespace lancer
