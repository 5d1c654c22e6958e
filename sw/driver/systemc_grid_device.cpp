#include "driver/systemc_grid_device.h"

#include "driver/systemc_traversal_device_impl.h"
#include "grid/rt_grid_unit.h"

namespace lancer {

template class SystemCTraversalDevice<fx::GridImage, sc::rt_grid_unit>;

template <>
std::unique_ptr<GridDevice> makeSystemCDevice<fx::GridUnit>(SystemCImpl impl) {
  return std::make_unique<SystemCGridDevice>(impl);
}
template <>
bool systemCRtlAvailable<fx::GridUnit>() {
  return SystemCGridDevice::rtlAvailable();
}

}  // namespace lancer
