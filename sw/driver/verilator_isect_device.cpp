#include "driver/verilator_isect_device.h"
#include "driver/wave_file.h"

#include <algorithm>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "Vrt_isect.h"
#include "driver/verilated_port.h"
#include "driver/verilated_unit.h"
#include "golden/stimulus.h"

namespace lancer {

namespace {

constexpr size_t kRayWords = size_t(fx::wireWords(fx::kIsectRayBits));
constexpr size_t kTriWords = size_t(fx::wireWords(fx::kIsectTriBits));
constexpr size_t kResWords = size_t(fx::wireWords(fx::kIsectResBits));

using RayPort = std::remove_reference_t<decltype(std::declval<Vrt_isect>().req_ray_i)>;
using TriPort = std::remove_reference_t<decltype(std::declval<Vrt_isect>().req_tri_i)>;
using ResPort = std::remove_reference_t<decltype(std::declval<Vrt_isect>().res_data_o)>;
static_assert(portWords<RayPort>() >= kRayWords && portWords<RayPort>() < kRayWords + 2,
              "req_ray_i does not match fx::kIsectRayBits: rebuild rt_pkg");
static_assert(portWords<TriPort>() >= kTriWords && portWords<TriPort>() < kTriWords + 2,
              "req_tri_i does not match fx::kIsectTriBits: rebuild rt_pkg");
static_assert(portWords<ResPort>() >= kResWords && portWords<ResPort>() < kResWords + 2,
              "res_data_o does not match fx::kIsectResBits: rebuild rt_pkg");

void idleInputs(Vrt_isect& top) {
  top.req_valid_i = 0;
  top.res_ready_i = 0;
}

}  // namespace

VerilatorIsectDevice::VerilatorIsectDevice() : unit_(std::make_unique<VerilatedUnit<Vrt_isect>>("rt_isect")) {
  unit_->reset(idleInputs);
}

VerilatorIsectDevice::~VerilatorIsectDevice() = default;

uint64_t VerilatorIsectDevice::totalCycles() const { return unit_->cycle(); }

StreamStats VerilatorIsectDevice::run(std::span<const IsectRequest> requests,
                                      std::vector<fx::IsectResult>& results,
                                      const StreamOptions& options) {
  StreamStats stats;
  const size_t n = requests.size();
  if (n == 0) return stats;

  // Records are packed when offered and unpacked when taken, straight from and
  // into the ports: no image of the whole stream is kept. A port keeps its
  // value, so a ray (or triangle) equal to the previous request's is not
  // packed again: streams of one ray against its candidate triangles pay once.
  if (results.capacity() < results.size() + n) {
    results.reserve(std::max(results.size() + n, 2 * results.capacity()));
  }
  fx::RayWire rayWire;  // fixed-size images: packing allocates nothing
  fx::TriWire triWire;
  fx::ResWire resWire;
  const fx::QRay* portRay = nullptr;
  const fx::QTriangle* portTri = nullptr;

  VerilatedUnit<Vrt_isect>& unit = *unit_;
  Vrt_isect& top = unit.top();
  unit.select();  // a run does not reset the model: select its context here
  unit.openWave(nextWaveFile(options.wavePath));

  std::mt19937_64 rng(options.seed);
  fx::Coin idle(options.inputIdleProbability, rng);
  fx::Coin stall(options.outputStallProbability, rng);

  // Without a transfer for this long the RTL has lost a request or a result
  // (a stalled stream moves every 1 / (1 - p) cycles: 10^4 at p = 0.9999).
  // Stall or idle probabilities of 1 never move, and end here.
  const uint64_t kWatchdog = 1000000;
  size_t offered = 0;  // index of the request on offer, or of the next one
  bool offering = false;
  size_t taken = 0;
  uint64_t firstCycle = 0, lastProgress = unit.cycle();
  bool started = false;

  try {
    while (taken < n) {
      // Producer: offers the next request, unless idling; keeps an offer until taken.
      if (!offering && offered < n && !idle()) {
        const IsectRequest& req = requests[offered];
        if (!portRay || !(req.ray == *portRay)) {
          fx::packWire(req.ray, rayWire);
          writePort(top.req_ray_i, rayWire.data(), kRayWords);
          portRay = &req.ray;
        }
        if (!portTri || !(req.tri == *portTri)) {
          fx::packWire(req.tri, triWire);
          writePort(top.req_tri_i, triWire.data(), kTriWords);
          portTri = &req.tri;
        }
        offering = true;
        if (!started) {
          started = true;
          firstCycle = unit.cycle();
        }
      }
      top.req_valid_i = offering;
      // Consumer: ready unless stalling.
      const bool ready = !stall();
      top.res_ready_i = ready;
      unit.settle();  // req_ready_o depends on res_ready_i

      const bool reqFire = offering && top.req_ready_o;
      const bool resFire = top.res_valid_o && ready;
      if (resFire) {
        if (taken >= stats.requests) throw std::runtime_error("rtl: a result without a request");
        readPort(top.res_data_o, resWire.data(), kResWords);
        fx::unpackResult(resWire, results.emplace_back());
        ++taken;
      }
      if (offering && !reqFire) ++stats.inputStalls;
      const uint64_t edge = unit.cycle();
      unit.tick();
      if (reqFire) {
        offering = false;
        ++offered;
        ++stats.requests;
      }
      if (reqFire || resFire) lastProgress = unit.cycle();
      if (taken == n) stats.cycles = edge - firstCycle + 1;
      if (unit.cycle() - lastProgress > kWatchdog) {
        throw std::runtime_error(fmt::format(
            "rtl: no progress for {} cycles ({} of {} requests accepted, {} results taken)",
            kWatchdog, stats.requests, n, taken));
      }
    }
  } catch (...) {
    unit.closeWave();
    throw;
  }
  idleInputs(top);
  unit.settle();
  unit.closeWave();

  stats.results = taken;
  return stats;
}

}  // namespace lancer
