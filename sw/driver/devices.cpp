#include "driver/devices.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "common/error.h"
#include "driver/golden_device.h"

namespace lancer {

std::vector<std::string> isectDeviceNames() { return {"golden"}; }

std::unique_ptr<IsectDevice> makeIsectDevice(const std::string& name) {
  if (name == "golden") return std::make_unique<GoldenIsectDevice>();
  throw InputError(fmt::format("unknown model '{}' (available: {})", name, fmt::join(isectDeviceNames(), ", ")));
}

}  // namespace lancer
