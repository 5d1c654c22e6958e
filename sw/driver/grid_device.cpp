#include "driver/grid_device.h"

namespace lancer {

GridRunStats GoldenGridDevice::run(const fx::GridImage& image, std::span<const fx::QRay> rays,
                                   std::vector<fx::GridTrace>& traces, const GridRunOptions&) {
  GridRunStats stats;
  stats.cycleAccurate = false;
  traces.clear();
  traces.reserve(rays.size());
  for (const fx::QRay& ray : rays) {
    traces.push_back(fx::traverseGrid(image, ray));
    const fx::GridTrace& t = traces.back();
    stats.voxelSteps += t.cells.size();
    stats.cellReads += t.cells.size();
    stats.indexReads += t.tests;
    stats.triangleReads += t.tests;
    stats.isectTests += t.tests;
  }
  stats.rays = rays.size();
  return stats;
}

}  // namespace lancer
