#include "driver/devices.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "driver/golden_device.h"

// LANCER_HW_MODELS=0: a build without the Verilated RTL and the SystemC models
// (cmake -DLANCER_HW_MODELS=OFF, the sanitizer tree); golden is the one model.
#ifndef LANCER_HW_MODELS
#define LANCER_HW_MODELS 1
#endif
#if LANCER_HW_MODELS
#include "driver/systemc_grid_device.h"
#include "driver/systemc_isect_device.h"
#include "driver/systemc_octree_device.h"
#include "driver/verilator_grid_device.h"
#include "driver/verilator_isect_device.h"
#include "driver/verilator_octree_device.h"
#endif

namespace lancer {

namespace {

[[noreturn]] void unknownModel(const std::string& name, const char* unit, const std::vector<std::string>& names) {
  throw InputError(
      fmt::format("unknown model '{}' for the {} (available: {})", name, unit, fmt::join(names, ", ")));
}

#if LANCER_HW_MODELS
// The four models of one unit, by name: its golden model, its SystemC device
// (the cycle model, or the Verilated RTL in SystemC where the build has it) and
// its Verilated device.
template <class Base, class Golden, class SystemC, class Verilator>
struct UnitModels {
  static std::vector<std::string> names() {
    std::vector<std::string> names{"golden", "systemc", "rtl"};
    if (SystemC::rtlAvailable()) names.push_back("rtl-systemc");
    return names;
  }

  // Throws InputError for an unknown name; `unit` names the unit in the message.
  static std::unique_ptr<Base> make(const std::string& name, const char* unit) {
    if (name == "golden") return std::make_unique<Golden>();
    if (name == "systemc") return std::make_unique<SystemC>(SystemC::Impl::Model);
    if (name == "rtl") return std::make_unique<Verilator>();
    if (name == "rtl-systemc" && SystemC::rtlAvailable()) return std::make_unique<SystemC>(SystemC::Impl::Rtl);
    unknownModel(name, unit, names());
  }
};

using IsectModels = UnitModels<IsectDevice, GoldenIsectDevice, SystemCIsectDevice, VerilatorIsectDevice>;
using GridModels = UnitModels<GridDevice, GoldenGridDevice, SystemCGridDevice, VerilatorGridDevice>;
using OctreeModels = UnitModels<OctreeDevice, GoldenOctreeDevice, SystemCOctreeDevice, VerilatorOctreeDevice>;
#else
template <class Base, class Golden>
struct UnitModels {
  static std::vector<std::string> names() { return {"golden"}; }
  static std::unique_ptr<Base> make(const std::string& name, const char* unit) {
    if (name == "golden") return std::make_unique<Golden>();
    unknownModel(name, unit, names());
  }
};
using IsectModels = UnitModels<IsectDevice, GoldenIsectDevice>;
using GridModels = UnitModels<GridDevice, GoldenGridDevice>;
using OctreeModels = UnitModels<OctreeDevice, GoldenOctreeDevice>;
#endif

}  // namespace

std::vector<std::string> isectDeviceNames() { return IsectModels::names(); }
std::unique_ptr<IsectDevice> makeIsectDevice(const std::string& name) {
  return IsectModels::make(name, "intersection pipeline");
}

std::vector<std::string> gridDeviceNames() { return GridModels::names(); }
std::unique_ptr<GridDevice> makeGridDevice(const std::string& name) { return GridModels::make(name, "grid unit"); }

std::vector<std::string> octreeDeviceNames() { return OctreeModels::names(); }
std::unique_ptr<OctreeDevice> makeOctreeDevice(const std::string& name) {
  return OctreeModels::make(name, "octree unit");
}

}  // namespace lancer
