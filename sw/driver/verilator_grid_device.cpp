#include "driver/verilator_grid_device.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "Vrt_grid.h"
#include "driver/verilated_port.h"
#include "common/error.h"
#include "golden/stimulus.h"
#include "verilated.h"
#include "verilated_fst_c.h"

#ifndef LANCER_GRID_RAYS_IN_FLIGHT
#error "LANCER_GRID_RAYS_IN_FLIGHT must come from rt_grid_vlt (rtl/CMakeLists.txt)"
#endif

namespace lancer {

namespace {

constexpr size_t kRayWords = size_t(fx::wireWords(fx::kIsectRayBits));
constexpr size_t kTriWords = size_t(fx::wireWords(fx::kIsectTriBits));
constexpr size_t kCellWords = size_t(fx::wireWords(fx::kGridCellBits));
constexpr size_t kVisitWords = size_t(fx::wireWords(fx::kGridVisitBits));
constexpr size_t kResWords = size_t(fx::wireWords(fx::kGridResultBits));

// Bit offset of field `index` in a record: the first field is the most significant.
constexpr int fieldLsb(std::span<const fx::FieldSpec> fields, size_t index) {
  int lsb = 0;
  for (size_t i = index + 1; i < fields.size(); ++i) lsb += fields[i].width * fields[i].count;
  return lsb;
}

// The two records that cross a port every cycle fit 64 bits: their fields are
// placed and taken directly (the generic packers of golden/records.h agree;
// the tests compare every visit and every cell the unit reads).
static_assert(fx::kGridCellBits <= 64 && fx::kGridVisitBits <= 64);
constexpr int kCellFirstLsb = fieldLsb(fx::kGridCellFields, 0);
constexpr int kCellCountLsb = fieldLsb(fx::kGridCellFields, 1);
constexpr int kVisitRayLsb = fieldLsb(fx::kGridVisitFields, 0);
constexpr int kVisitCellLsb = fieldLsb(fx::kGridVisitFields, 1);
constexpr uint64_t kVisitCellMask = (uint64_t(1) << fx::kGridVisitFields[1].width) - 1;
static_assert(fx::kGridCellFields[0].width == 32 && fx::kGridCellFields[1].width == 32 &&
              fx::kGridVisitFields[0].width == 32 && kVisitRayLsb + 32 == fx::kGridVisitBits);

}  // namespace

VerilatorGridDevice::VerilatorGridDevice() : context_(std::make_unique<VerilatedContext>()) {
  context_->traceEverOn(true);
  context_->fatalOnError(false);  // a failed assertion becomes an exception
  top_ = std::make_unique<Vrt_grid>(context_.get(), "rt_grid");
  reset();
}

VerilatorGridDevice::~VerilatorGridDevice() {
  if (wave_) wave_->close();
  if (top_) top_->final();
}

int VerilatorGridDevice::maxRaysInFlight() const { return LANCER_GRID_RAYS_IN_FLIGHT; }

void VerilatorGridDevice::reset() {
  top_->clk_i = 0;
  top_->rst_ni = 0;
  top_->ray_valid_i = 0;
  top_->res_ready_i = 0;
  top_->visit_ready_i = 0;
  top_->cell_req_ready_i = 1;
  top_->idx_req_ready_i = 1;
  top_->tri_req_ready_i = 1;
  top_->cell_rsp_valid_i = 0;
  top_->idx_rsp_valid_i = 0;
  top_->tri_rsp_valid_i = 0;
  top_->cfg_slots_i = LANCER_GRID_RAYS_IN_FLIGHT;
  top_->cfg_res_i = 1 | (1 << 9) | (1 << 18);
  top_->eval();
  for (int i = 0; i < 2; ++i) tick();
  top_->rst_ni = 1;
  top_->eval();
  tick();
  checkAssertions();
}

void VerilatorGridDevice::tick() {
  if (wave_) wave_->dump(2 * cycle_);
  context_->time(2 * cycle_ + 1);
  top_->clk_i = 1;
  top_->eval();
  if (wave_) wave_->dump(2 * cycle_ + 1);
  ++cycle_;
  context_->time(2 * cycle_);
  top_->clk_i = 0;
}

void VerilatorGridDevice::checkAssertions() const {
  if (context_->gotError()) {
    throw std::runtime_error(
        fmt::format("rtl: an assertion of rt_grid failed near cycle {} (see the %Error line above)", cycle_));
  }
}

TraversalRunStats VerilatorGridDevice::run(const fx::GridImage& image, std::span<const fx::QRay> rays,
                                      std::vector<fx::GridTrace>& traces, const TraversalRunOptions& options) {
  const int maxSlots = maxRaysInFlight();
  if (options.raysInFlight < 0 || options.raysInFlight > maxSlots) {
    throw InputError(fmt::format("rays in flight {} is out of range: the RTL grid unit was built with {} ray slots "
                                 "(use 1..{}, or 0 for all; rebuild with -DLANCER_GRID_RAYS_IN_FLIGHT for more)",
                                 options.raysInFlight, maxSlots, maxSlots));
  }
  if (options.memLatency < 1 || options.memLatencyJitter < 0) {
    throw InputError(fmt::format("memory latency {} (jitter {}) is out of range: latency >= 1, jitter >= 0",
                                 options.memLatency, options.memLatencyJitter));
  }
  for (int a = 0; a < 3; ++a) {
    if (image.res[a] < 1 || image.res[a] > fx::kGridResMax) {
      throw InputError(fmt::format("grid resolution {} on axis {} is out of range 1..{}", image.res[a], a,
                                   fx::kGridResMax));
    }
  }

  TraversalRunStats stats;
  const size_t n = rays.size();
  traces.assign(n, fx::GridTrace{});
  stats.rays = n;
  if (n == 0) return stats;

  reset();
  top_->cfg_res_i = uint32_t(image.res[0]) | (uint32_t(image.res[1]) << 9) | (uint32_t(image.res[2]) << 18);
  top_->cfg_slots_i = options.raysInFlight == 0 ? maxSlots : options.raysInFlight;
  top_->eval();

  if (!options.stream.wavePath.empty()) {
    wave_ = std::make_unique<VerilatedFstC>();
    top_->trace(wave_.get(), 99);
    wave_->open(options.stream.wavePath.c_str());
    if (!wave_->isOpen()) {
      wave_.reset();
      throw std::runtime_error("rtl: cannot write waveform " + options.stream.wavePath);
    }
  }

  std::mt19937_64 rng(options.stream.seed);
  fx::Coin idle(options.stream.inputIdleProbability, rng);
  fx::Coin stallRes(options.stream.outputStallProbability, rng);
  fx::Coin stallVisit(options.stream.outputStallProbability, rng);
  fx::MemoryReadPort cellPort(options.memLatency, options.memLatencyJitter, options.stream.seed * 3 + 1);
  fx::MemoryReadPort idxPort(options.memLatency, options.memLatencyJitter, options.stream.seed * 3 + 2);
  fx::MemoryReadPort triPort(options.memLatency, options.memLatencyJitter, options.stream.seed * 3 + 3);

  // Wire images packed once per run; records cross the ports by block copies
  // and the allocation-free packers of golden/records.h (nothing is allocated per cycle).
  std::vector<fx::TriWire> triWires(image.triangles.size());
  for (size_t t = 0; t < triWires.size(); ++t) fx::packWire(image.triangles[t], triWires[t]);
  std::array<uint32_t, kRayWords> rayWire{};
  std::array<uint32_t, kCellWords> cellWire{};
  std::array<uint32_t, kVisitWords> visitWire{};
  std::array<uint32_t, kResWords> resWire{};
  std::array<fx::u128, fx::valueCount(fx::kGridResFields)> res{};

  std::vector<uint8_t> finished(n, 0);
  std::vector<uint32_t> resultCells(n, 0);
  const uint64_t kWatchdog = 1000000;
  size_t offered = 0, results = 0;
  bool offering = false, started = false;
  uint64_t firstCycle = 0, lastProgress = cycle_;

  auto checkAddr = [](const char* region, uint32_t addr, size_t size) {
    if (addr >= size) {
      throw std::runtime_error(fmt::format("rtl: {} read at {} outside the image ({} entries)", region, addr, size));
    }
  };

  while (results < n || !cellPort.idle() || !idxPort.idle() || !triPort.idle() || top_->visit_valid_o) {
    // Producer: the next ray, unless idling; an offer holds until taken.
    if (!offering && offered < n && !idle()) {
      fx::QRay wireRay = rays[offered];
      wireRay.id = uint32_t(offered);
      fx::packWire(wireRay, rayWire);
      writePort(top_->ray_data_i, rayWire.data(), kRayWords);
      offering = true;
      if (!started) {
        started = true;
        firstCycle = cycle_;
      }
    }
    top_->ray_valid_i = offering;
    const bool resReady = !stallRes();
    const bool visitReady = !stallVisit();
    top_->res_ready_i = resReady;
    top_->visit_ready_i = visitReady;

    // Memory responses due in this cycle.
    uint32_t addr = 0, tag = 0;
    top_->cell_rsp_valid_i = cellPort.respond(cycle_, addr, tag);
    if (top_->cell_rsp_valid_i) {
      checkAddr("cell table", addr, image.cells.size());
      const fx::GridCell& c = image.cells[addr];
      const uint64_t cell = (uint64_t(c.first) << kCellFirstLsb) | (uint64_t(c.count) << kCellCountLsb);
      cellWire[0] = uint32_t(cell);
      if (kCellWords > 1) cellWire[kCellWords - 1] = uint32_t(cell >> 32);
      writePort(top_->cell_rsp_data_i, cellWire.data(), kCellWords);
      top_->cell_rsp_tag_i = tag;
    }
    top_->idx_rsp_valid_i = idxPort.respond(cycle_, addr, tag);
    if (top_->idx_rsp_valid_i) {
      checkAddr("index list", addr, image.indices.size());
      top_->idx_rsp_data_i = image.indices[addr];
      top_->idx_rsp_tag_i = tag;
    }
    top_->tri_rsp_valid_i = triPort.respond(cycle_, addr, tag);
    if (top_->tri_rsp_valid_i) {
      checkAddr("triangle table", addr, image.triangles.size());
      writePort(top_->tri_rsp_data_i, triWires[addr].data(), kTriWords);
      top_->tri_rsp_tag_i = tag;
    }
    top_->eval();

    // Handshakes of this cycle.
    const bool rayFire = offering && top_->ray_ready_o;
    bool progress = rayFire;
    if (top_->cell_req_valid_o) {
      cellPort.request(cycle_, top_->cell_req_addr_o, top_->cell_req_tag_o);
      ++stats.nodeReads;
    }
    if (top_->idx_req_valid_o) {
      idxPort.request(cycle_, top_->idx_req_addr_o, top_->idx_req_tag_o);
      ++stats.indexReads;
    }
    if (top_->tri_req_valid_o) {
      triPort.request(cycle_, top_->tri_req_addr_o, top_->tri_req_tag_o);
      ++stats.triangleReads;
    }
    if (top_->perf_isect_fire_o) {
      ++stats.isectTests;
      ++stats.isectBusyCycles;
      progress = true;
    }
    if (started && top_->perf_step_ready_o) ++stats.stepReadyCycles;
    const uint64_t edge = cycle_;
    if (top_->visit_valid_o && visitReady) {
      readPort(top_->visit_data_o, visitWire.data(), kVisitWords);
      const uint64_t visit = uint64_t(visitWire[0]) | (kVisitWords > 1 ? uint64_t(visitWire[kVisitWords - 1]) << 32 : 0);
      const size_t k = size_t(uint32_t(visit >> kVisitRayLsb));
      if (k >= offered) {
        throw std::runtime_error(fmt::format("rtl: a visit record for ray {} that is not in flight", k));
      }
      traces[k].visits.push_back(uint32_t((visit >> kVisitCellLsb) & kVisitCellMask));
      ++stats.steps;
      stats.cycles = edge - firstCycle + 1;
      progress = true;
    }
    if (top_->res_valid_o && resReady) {
      readPort(top_->res_data_o, resWire.data(), kResWords);
      fx::unpackFields(fx::kGridResFields, resWire, res);
      const size_t k = size_t(res[0]);
      if (k >= offered || finished[k]) {
        throw std::runtime_error(fmt::format("rtl: a result for ray {} that is not in flight", k));
      }
      finished[k] = 1;
      resultCells[k] = uint32_t(res[1]);
      fx::GridTrace& t = traces[k];
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
      stats.cycles = edge - firstCycle + 1;
      progress = true;
    }
    tick();
    checkAssertions();
    if (rayFire) {
      offering = false;
      ++offered;
    }
    if (progress) lastProgress = cycle_;
    if (cycle_ - lastProgress > kWatchdog) {
      throw std::runtime_error(fmt::format("rtl: no progress for {} cycles ({} of {} rays accepted, {} results)",
                                           kWatchdog, offered, n, results));
    }
  }
  top_->ray_valid_i = 0;
  top_->res_ready_i = 0;
  top_->visit_ready_i = 0;
  top_->cell_rsp_valid_i = 0;
  top_->idx_rsp_valid_i = 0;
  top_->tri_rsp_valid_i = 0;
  top_->eval();
  if (wave_) {
    wave_->dump(2 * cycle_);
    wave_->close();
    wave_.reset();
  }
  for (size_t k = 0; k < n; ++k) {
    if (resultCells[k] != traces[k].visits.size()) {
      throw std::runtime_error(fmt::format("rtl: ray {} reports {} cells but {} visit records came out", k,
                                           resultCells[k], traces[k].visits.size()));
    }
  }
  return stats;
}

}  // namespace lancer
