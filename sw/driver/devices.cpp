#include "driver/devices.h"

#include <functional>
#include <string_view>
#include <tuple>

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
#include "driver/systemc_isect_device.h"
#include "driver/verilator_isect_device.h"
#endif

namespace lancer {

namespace {

// One model of a unit: its name and how to make it.
template <class Base>
struct Model {
  const char* name;
  std::function<std::unique_ptr<Base>()> make;
};

template <class Base>
std::vector<std::string> namesOf(const std::vector<Model<Base>>& models) {
  std::vector<std::string> names;
  for (const Model<Base>& m : models) names.push_back(m.name);
  return names;
}

template <class Base>
std::unique_ptr<Base> pick(const std::vector<Model<Base>>& models, const std::string& name, std::string_view unit) {
  for (const Model<Base>& m : models) {
    if (m.name == name) return m.make();
  }
  throw InputError(
      fmt::format("unknown model '{}' for the {} (available: {})", name, unit, fmt::join(namesOf(models), ", ")));
}

// golden, systemc, systemc-pins, rtl, and rtl-systemc where the build has it.
std::vector<Model<IsectDevice>> isectModels() {
  std::vector<Model<IsectDevice>> models{{"golden", [] { return std::make_unique<GoldenIsectDevice>(); }}};
#if LANCER_HW_MODELS
  models.push_back({"systemc", [] { return std::make_unique<SystemCIsectDevice>(SystemCIsectDevice::Impl::Model); }});
  models.push_back(
      {"systemc-pins", [] { return std::make_unique<SystemCIsectDevice>(SystemCIsectDevice::Impl::Pins); }});
  models.push_back({"rtl", [] { return std::make_unique<VerilatorIsectDevice>(); }});
  if (SystemCIsectDevice::rtlAvailable()) {
    models.push_back(
        {"rtl-systemc", [] { return std::make_unique<SystemCIsectDevice>(SystemCIsectDevice::Impl::Rtl); }});
  }
#endif
  return models;
}

template <class Unit>
std::vector<Model<DeviceOf<Unit>>> traversalModels() {
  std::vector<Model<DeviceOf<Unit>>> models{
      {"golden", [] { return std::make_unique<GoldenTraversalDevice<typename Unit::Image>>(); }}};
#if LANCER_HW_MODELS
  models.push_back({"systemc", [] { return makeSystemCDevice<Unit>(SystemCImpl::Model); }});
  models.push_back({"systemc-pins", [] { return makeSystemCDevice<Unit>(SystemCImpl::Pins); }});
  models.push_back({"rtl", [] { return makeVerilatorDevice<Unit>(); }});
  if (systemCRtlAvailable<Unit>()) {
    models.push_back({"rtl-systemc", [] { return makeSystemCDevice<Unit>(SystemCImpl::Rtl); }});
  }
#endif
  return models;
}

}  // namespace

std::vector<std::string> isectDeviceNames() { return namesOf(isectModels()); }
std::unique_ptr<IsectDevice> makeIsectDevice(const std::string& name) {
  return pick(isectModels(), name, "intersection pipeline");
}

template <class Unit>
std::vector<std::string> traversalDeviceNames() {
  return namesOf(traversalModels<Unit>());
}

template <class Unit>
std::unique_ptr<DeviceOf<Unit>> makeTraversalDevice(const std::string& name) {
  return pick(traversalModels<Unit>(), name, fmt::format("{} unit", Unit::kNames.unit));
}

// Both templates for every unit of fx::TraversalUnits: the explicit
// instantiation of all() emits them.
template <class Units>
struct TraversalDeviceTables;
template <class... Units>
struct TraversalDeviceTables<std::tuple<Units...>> {
  static auto all() { return std::tuple{std::pair{&traversalDeviceNames<Units>, &makeTraversalDevice<Units>}...}; }
};
template struct TraversalDeviceTables<fx::TraversalUnits>;

}  // namespace lancer
