#include "driver/verilator_octree_device.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "Vrt_octree.h"
#include "common/error.h"
#include "driver/verilated_port.h"
#include "driver/verilated_unit.h"

#ifndef LANCER_OCTREE_RAYS_IN_FLIGHT
#error "LANCER_OCTREE_RAYS_IN_FLIGHT must come from rt_octree_vlt (rtl/CMakeLists.txt)"
#endif

namespace lancer {

namespace {

constexpr size_t kRayWords = fx::kIsectRayWords;
constexpr size_t kTriWords = fx::kIsectTriWords;
constexpr size_t kNodeWords = size_t(fx::wireWords(fx::kOctreeNodeBits));
constexpr size_t kResWords = size_t(fx::wireWords(fx::kOctreeResultBits));
constexpr size_t kResValues = fx::valueCount(fx::kOctreeResFields);
static_assert(kNodeWords == 2, "octree_node_t is one 64-bit word");
static_assert(fx::kOctreeVisitBits == 64, "octree_visit_t is {ray_id, node_id}, one 64-bit port");

// octree_node_t as the 64-bit integer of its wire image (fx::packFields).
uint64_t packNode(const fx::OctreeNode& node) {
  const fx::u128 values[] = {node.leaf ? 1u : 0u, node.count, node.first};
  std::array<uint32_t, kNodeWords> wire{};
  fx::packFields(fx::kOctreeNodeFields, values, wire);
  return uint64_t(wire[0]) | (uint64_t(wire[1]) << 32);
}

void idleInputs(Vrt_octree& top) {
  top.ray_valid_i = 0;
  top.res_ready_i = 0;
  top.visit_ready_i = 0;
  top.node_req_ready_i = 1;
  top.idx_req_ready_i = 1;
  top.tri_req_ready_i = 1;
  top.node_rsp_valid_i = 0;
  top.idx_rsp_valid_i = 0;
  top.tri_rsp_valid_i = 0;
  top.cfg_slots_i = LANCER_OCTREE_RAYS_IN_FLIGHT;
  top.cfg_root_i = 0;
}

}  // namespace

VerilatorOctreeDevice::VerilatorOctreeDevice()
    : unit_(std::make_unique<VerilatedUnit<Vrt_octree>>("rt_octree")) {
  unit_->reset(idleInputs);
}

VerilatorOctreeDevice::~VerilatorOctreeDevice() = default;

int VerilatorOctreeDevice::maxRaysInFlight() const { return LANCER_OCTREE_RAYS_IN_FLIGHT; }

TraversalRunStats VerilatorOctreeDevice::run(const fx::OctreeImage& image, std::span<const fx::QRay> rays,
                                             std::vector<fx::TraversalTrace>& traces,
                                             const TraversalRunOptions& options) {
  const int maxSlots = maxRaysInFlight();
  checkTraversalOptions(options, maxSlots, "octree", "LANCER_OCTREE_RAYS_IN_FLIGHT");
  if (image.nodes.empty()) throw InputError("the octree image has no nodes (node 0 is the root)");
  for (const fx::QRay& ray : rays) {
    if (ray.dir[0] == 0 && ray.dir[1] == 0 && ray.dir[2] == 0) {
      throw InputError(fmt::format("ray {} has a zero direction: the octree unit needs a non-zero component", ray.id));
    }
  }

  TraversalRunStats stats;
  const size_t n = rays.size();
  traces.assign(n, fx::TraversalTrace{});
  stats.rays = n;
  if (n == 0) return stats;

  // The image as the ports carry it, packed once: nodes (a child group is
  // eight consecutive ones) and triangles.
  std::vector<uint64_t> nodeWire(image.nodes.size());
  for (size_t i = 0; i < image.nodes.size(); ++i) nodeWire[i] = packNode(image.nodes[i]);
  std::vector<uint32_t> triWire(image.triangles.size() * kTriWords);
  for (size_t i = 0; i < image.triangles.size(); ++i) {
    fx::packWire(image.triangles[i], std::span<uint32_t>(triWire).subspan(i * kTriWords, kTriWords));
  }

  VerilatedUnit<Vrt_octree>& unit = *unit_;
  Vrt_octree& top = unit.top();
  unit.reset(idleInputs);
  top.cfg_slots_i = options.raysInFlight == 0 ? maxSlots : options.raysInFlight;
  top.cfg_root_i = nodeWire[0];
  unit.settle();
  unit.openWave(options.stream.wavePath);

  TraversalStimulus stim(options);
  std::vector<uint8_t> finished(n, 0);
  std::vector<uint32_t> resultNodes(n, 0);
  std::array<uint32_t, kResWords> resWire{};
  std::array<fx::u128, kResValues> res{};
  fx::RayWire rayWire{};
  size_t offered = 0, results = 0;
  bool offering = false, started = false;
  uint64_t firstCycle = 0, lastProgress = unit.cycle();

  auto fail = [&](const std::string& what) {
    unit.closeWave();
    throw std::runtime_error("rtl: " + what);
  };

  while (results < n || !stim.memoryIdle() || top.visit_valid_o) {
    // At the start of the cycle every output read here depends on registers only.
    const uint64_t cycle = unit.cycle();
    // Producer: the next ray, unless idling; an offer holds until taken.
    if (!offering && offered < n && !stim.idle()) {
      fx::QRay wireRay = rays[offered];
      wireRay.id = uint32_t(offered);
      fx::packWire(wireRay, rayWire);
      writePort(top.ray_data_i, rayWire.data(), kRayWords);
      offering = true;
      if (!started) {
        started = true;
        firstCycle = cycle;
      }
    }
    top.ray_valid_i = offering;
    const bool resReady = !stim.stallRes();
    const bool visitReady = !stim.stallVisit();
    top.res_ready_i = resReady;
    top.visit_ready_i = visitReady;

    // Handshakes of this cycle. The memory ports are always ready.
    const bool rayFire = offering && top.ray_ready_o;
    bool progress = rayFire;
    if (top.node_req_valid_o) {
      stim.nodePort.request(cycle, top.node_req_addr_o, top.node_req_tag_o);
      ++stats.nodeReads;
    }
    if (top.idx_req_valid_o) {
      stim.idxPort.request(cycle, top.idx_req_addr_o, top.idx_req_tag_o);
      ++stats.indexReads;
    }
    if (top.tri_req_valid_o) {
      stim.triPort.request(cycle, top.tri_req_addr_o, top.tri_req_tag_o);
      ++stats.triangleReads;
    }
    if (top.perf_step_ready_o) ++stats.stepReadyCycles;
    if (top.visit_valid_o && visitReady) {
      const uint64_t v = top.visit_data_o;  // {ray_id, node_id}
      const size_t k = size_t(v >> 32);
      if (k >= offered) fail(fmt::format("a visit record for ray {} that was never accepted", k));
      traces[k].visits.push_back(uint32_t(v));
      ++stats.steps;
      stats.cycles = cycle - firstCycle + 1;
      progress = true;
    }
    if (top.res_valid_o && resReady) {
      readPort(top.res_data_o, resWire.data(), kResWords);
      fx::unpackFields(fx::kOctreeResFields, resWire, res);
      const size_t k = size_t(res[0]);
      if (k >= offered || finished[k]) fail(fmt::format("a result for ray {} that is not in flight", k));
      finished[k] = 1;
      resultNodes[k] = uint32_t(res[1]);
      fx::TraversalTrace& t = traces[k];
      t.tests = uint64_t(res[2]);
      if (res[3]) {
        fx::IsectResult hit;
        hit.rayId = rays[k].id;
        hit.primId = uint32_t(res[4]);
        hit.hit = true;
        hit.tNum = res[5];
        hit.det = res[6];
        hit.uNum = res[7];
        hit.vNum = res[8];
        t.hit = hit;
      }
      ++results;
      stats.cycles = cycle - firstCycle + 1;
      progress = true;
    }

    // Memory responses due in this cycle.
    uint32_t addr = 0, tag = 0;
    top.node_rsp_valid_i = stim.nodePort.respond(cycle, addr, tag);
    if (top.node_rsp_valid_i) {
      if (uint64_t(addr) + fx::kOctreeChildren > nodeWire.size()) {
        fail(fmt::format("child group read at {} outside the node table ({} nodes)", addr, nodeWire.size()));
      }
      std::memcpy(top.node_rsp_data_i.data(), &nodeWire[addr], fx::kOctreeChildren * sizeof(uint64_t));
      top.node_rsp_tag_i = tag;
    }
    top.idx_rsp_valid_i = stim.idxPort.respond(cycle, addr, tag);
    if (top.idx_rsp_valid_i) {
      if (addr >= image.indices.size()) {
        fail(fmt::format("index list read at {} outside the image ({} entries)", addr, image.indices.size()));
      }
      top.idx_rsp_data_i = image.indices[addr];
      top.idx_rsp_tag_i = tag;
    }
    top.tri_rsp_valid_i = stim.triPort.respond(cycle, addr, tag);
    if (top.tri_rsp_valid_i) {
      if (addr >= image.triangles.size()) {
        fail(fmt::format("triangle table read at {} outside the image ({} entries)", addr, image.triangles.size()));
      }
      writePort(top.tri_rsp_data_i, &triWire[size_t(addr) * kTriWords], kTriWords);
      top.tri_rsp_tag_i = tag;
    }

    unit.settle();
    // perf_isect_fire_o = tri_rsp_valid_i && rt_isect's req_ready_o: combinational in an input.
    if (top.perf_isect_fire_o) {
      ++stats.isectTests;
      ++stats.isectBusyCycles;
      progress = true;
    }
    try {
      unit.tick();
    } catch (...) {
      unit.closeWave();
      throw;
    }
    if (rayFire) {
      offering = false;
      ++offered;
    }
    if (progress) lastProgress = unit.cycle();
    if (unit.cycle() - lastProgress > kTraversalWatchdogCycles) {
      fail(fmt::format("no progress for {} cycles ({} of {} rays accepted, {} results)", kTraversalWatchdogCycles,
                       offered, n, results));
    }
  }
  idleInputs(top);
  top.cfg_slots_i = options.raysInFlight == 0 ? maxSlots : options.raysInFlight;
  top.cfg_root_i = nodeWire[0];
  unit.settle();
  unit.closeWave();
  for (size_t k = 0; k < n; ++k) {
    if (resultNodes[k] != traces[k].visits.size()) {
      throw std::runtime_error(fmt::format("rtl: ray {} reports {} nodes but {} visit records came out", k,
                                           resultNodes[k], traces[k].visits.size()));
    }
  }
  return stats;
}

}  // namespace lancer
