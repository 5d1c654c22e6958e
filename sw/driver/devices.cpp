#include "driver/devices.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "driver/golden_device.h"
#include "driver/systemc_grid_device.h"
#include "driver/systemc_isect_device.h"
#include "driver/systemc_octree_device.h"
#include "driver/verilator_grid_device.h"
#include "driver/verilator_isect_device.h"
#include "driver/verilator_octree_device.h"

namespace lancer {

namespace {

[[noreturn]] void unknownModel(const std::string& name, const std::vector<std::string>& names, const char* unit) {
  throw InputError(fmt::format("unknown model '{}' for the {} (available: {})", name, unit, fmt::join(names, ", ")));
}

}  // namespace

std::vector<std::string> isectDeviceNames() {
  std::vector<std::string> names{"golden", "systemc", "rtl"};
  if (SystemCIsectDevice::rtlAvailable()) names.push_back("rtl-systemc");
  return names;
}

std::unique_ptr<IsectDevice> makeIsectDevice(const std::string& name) {
  if (name == "golden") return std::make_unique<GoldenIsectDevice>();
  if (name == "systemc") return std::make_unique<SystemCIsectDevice>(SystemCIsectDevice::Impl::Model);
  if (name == "rtl") return std::make_unique<VerilatorIsectDevice>();
  if (name == "rtl-systemc" && SystemCIsectDevice::rtlAvailable()) {
    return std::make_unique<SystemCIsectDevice>(SystemCIsectDevice::Impl::Rtl);
  }
  unknownModel(name, isectDeviceNames(), "intersection pipeline");
}

std::vector<std::string> gridDeviceNames() {
  std::vector<std::string> names{"golden", "systemc", "rtl"};
  if (SystemCGridDevice::rtlAvailable()) names.push_back("rtl-systemc");
  return names;
}

std::unique_ptr<GridDevice> makeGridDevice(const std::string& name) {
  if (name == "golden") return std::make_unique<GoldenGridDevice>();
  if (name == "systemc") return std::make_unique<SystemCGridDevice>(SystemCGridDevice::Impl::Model);
  if (name == "rtl") return std::make_unique<VerilatorGridDevice>();
  if (name == "rtl-systemc" && SystemCGridDevice::rtlAvailable()) {
    return std::make_unique<SystemCGridDevice>(SystemCGridDevice::Impl::Rtl);
  }
  unknownModel(name, gridDeviceNames(), "grid unit");
}

std::vector<std::string> octreeDeviceNames() {
  std::vector<std::string> names{"golden", "systemc", "rtl"};
  if (SystemCOctreeDevice::rtlAvailable()) names.push_back("rtl-systemc");
  return names;
}

std::unique_ptr<OctreeDevice> makeOctreeDevice(const std::string& name) {
  if (name == "golden") return std::make_unique<GoldenOctreeDevice>();
  if (name == "systemc") return std::make_unique<SystemCOctreeDevice>(SystemCOctreeDevice::Impl::Model);
  if (name == "rtl") return std::make_unique<VerilatorOctreeDevice>();
  if (name == "rtl-systemc" && SystemCOctreeDevice::rtlAvailable()) {
    return std::make_unique<SystemCOctreeDevice>(SystemCOctreeDevice::Impl::Rtl);
  }
  unknownModel(name, octreeDeviceNames(), "octree unit");
}

}  // namespace lancer
