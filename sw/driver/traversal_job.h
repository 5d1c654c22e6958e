#pragma once

// The hardware job of a traversal unit (grid, octree): rays through the unit's
// model and its golden model, compared per ray bit for bit, with the unit's
// counters for the summary and the JSON report. One implementation for every
// unit; what differs per unit (names, image counters) is its descriptor
// (golden/unit.h).

#include <algorithm>
#include <bit>
#include <string>
#include <vector>

#include "driver/chip.h"
#include "driver/job.h"
#include "driver/traversal_device.h"

namespace lancer {

// A unit's memory image for a scene: the triangles and the native quadrics
// quantized, then the descriptor's build() with the --grid-res / --octree-*
// options (0: the golden model's heuristics).
template <class Unit>
typename Unit::Image buildImageFor(const Scene& scene, const Quantizer& quantizer, const AccelOptions& options) {
  return Unit::build(quantizer.quantizeTriangles(scene), options, quantizer.quantizeQuadrics(scene));
}

// The descriptor's figures of a unit's image (Unit::imageCounters: the grid's
// resolution, the octree's depth and nodes, ...), then its size in memory:
// each region's bytes, the whole image's (without the pages' padding), and
// the address bits its largest region needs (at most fx::kMemAddrBits, or the
// build would have refused it), as counters for the summary and the report.
template <class Unit>
std::vector<JobCounter> imageFigures(const typename Unit::Image& image) {
  std::vector<JobCounter> figures;
  for (const fx::ImageCounter& c : Unit::imageCounters(image)) figures.push_back({c.key, c.label, c.value});
  uint64_t bytes = 0, records = 1;
  const auto regions = regionsOf<Unit>(image);
  for (size_t i = 0; i < regions.size(); ++i) {
    const mem::Region& r = regions[i];
    if (i == mem::kQuadricRegion && r.records == 0) continue;  // a scene of triangles
    std::string key = r.name + "_image_bytes";
    std::replace(key.begin(), key.end(), ' ', '_');
    figures.push_back({key, "image: " + r.name, double(r.bytes())});
    bytes += r.bytes();
    records = std::max(records, r.records);
  }
  figures.push_back({"image_bytes", "image bytes", double(bytes)});
  figures.push_back({"address_bits_needed", "address bits needed", double(std::bit_width(records - 1))});
  return figures;
}

// The run options of a job's configuration (stream, memory, chip).
TraversalRunOptions traversalOptionsOf(const JobConfig& config);

// Runs every ray that entered the lattice (rays[k], id k) through `model` and
// `golden` and compares, per ray, bit for bit: the elements visited in order,
// the tests issued, and the closest hit record. `sharedMemory` (the path's
// memory hierarchy, if any) serves every batch. Throws InputError for a
// rays-in-flight count or memory latency the model cannot run. Instantiated
// for every unit of fx::TraversalUnits.
template <class Image>
JobResult runTraversalJob(const Image& image, std::span<const std::optional<QuantizedRay>> rays,
                          TraversalDevice<Image>& model, TraversalDevice<Image>& golden, const JobConfig& config,
                          const ProgressFn& onProgress = {}, mem::MemorySystem* sharedMemory = nullptr);

// The reproducer text of a mismatch: the ray, both visit sequences from the
// first difference, both hit records. `unit` is the unit's name ("grid"),
// `element` what it visits ("cells").
std::string describeTraversalMismatch(std::string_view unit, std::string_view element, const fx::QRay& ray,
                                      const fx::TraversalTrace& model, const fx::TraversalTrace& golden);

}  // namespace lancer
