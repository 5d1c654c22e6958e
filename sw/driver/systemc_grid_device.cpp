#include "driver/systemc_grid_device.h"

#include "driver/systemc_traversal_device_impl.h"
#include "grid/rt_grid_unit.h"

namespace lancer {

template <>
void SystemCGridDevice::checkImage(const fx::GridImage& image) {
  for (int a = 0; a < 3; ++a) {
    if (image.res[a] < 1 || image.res[a] > fx::kGridResMax) {
      throw InputError(fmt::format("grid resolution {} on axis {} is out of range 1..{}", image.res[a], a,
                                   fx::kGridResMax));
    }
  }
}

template class SystemCTraversalDevice<fx::GridImage, sc::rt_grid_unit>;

}  // namespace lancer
