#include "driver/verilator_isect_device.h"

#include <algorithm>
#include <cstring>
#include <random>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <fmt/format.h>

#include "Vrt_isect.h"
#include "driver/verilated_port.h"
#include "golden/stimulus.h"
#include "verilated.h"
#include "verilated_fst_c.h"

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


}  // namespace

VerilatorIsectDevice::VerilatorIsectDevice()
    : context_(std::make_unique<VerilatedContext>()) {
  context_->traceEverOn(true);    // waves may be asked for by any later run()
  context_->fatalOnError(false);  // a failed assertion becomes an exception, see tick()
  top_ = std::make_unique<Vrt_isect>(context_.get(), "rt_isect");
  reset();
}

VerilatorIsectDevice::~VerilatorIsectDevice() {
  if (wave_) wave_->close();
  if (top_) top_->final();
}

void VerilatorIsectDevice::reset() {
  top_->clk_i = 0;
  top_->rst_ni = 0;
  top_->req_valid_i = 0;
  top_->res_ready_i = 0;
  top_->eval();
  for (int i = 0; i < 2; ++i) tick();
  top_->rst_ni = 1;
  top_->eval();
  tick();
  checkAssertions();
}

void VerilatorIsectDevice::tick() {
  if (wave_) wave_->dump(2 * cycle_);
  context_->time(2 * cycle_ + 1);
  top_->clk_i = 1;
  top_->eval();
  if (wave_) wave_->dump(2 * cycle_ + 1);
  ++cycle_;
  context_->time(2 * cycle_);
  top_->clk_i = 0;
}

void VerilatorIsectDevice::checkAssertions() const {
  if (context_->gotError()) {
    throw std::runtime_error(fmt::format(
        "rtl: an assertion of rt_isect failed near cycle {} (see the %Error line above)", cycle_));
  }
}

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

  if (!options.wavePath.empty()) {
    wave_ = std::make_unique<VerilatedFstC>();
    top_->trace(wave_.get(), 99);
    wave_->open(options.wavePath.c_str());
    if (!wave_->isOpen()) {
      wave_.reset();
      throw std::runtime_error("rtl: cannot write waveform " + options.wavePath);
    }
  }

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
  uint64_t firstCycle = 0, lastProgress = cycle_;
  bool started = false;

  while (taken < n) {
    // Producer: offers the next request, unless idling; keeps an offer until taken.
    if (!offering && offered < n && !idle()) {
      const IsectRequest& req = requests[offered];
      if (!portRay || !(req.ray == *portRay)) {
        fx::packWire(req.ray, rayWire);
        writePort(top_->req_ray_i, rayWire.data(), kRayWords);
        portRay = &req.ray;
      }
      if (!portTri || !(req.tri == *portTri)) {
        fx::packWire(req.tri, triWire);
        writePort(top_->req_tri_i, triWire.data(), kTriWords);
        portTri = &req.tri;
      }
      offering = true;
      if (!started) {
        started = true;
        firstCycle = cycle_;
      }
    }
    top_->req_valid_i = offering;
    // Consumer: ready unless stalling.
    const bool ready = !stall();
    top_->res_ready_i = ready;
    top_->eval();  // settle req_ready_o, which depends on res_ready_i

    const bool reqFire = offering && top_->req_ready_o;
    const bool resFire = top_->res_valid_o && ready;
    if (resFire) {
      if (taken >= stats.requests) throw std::runtime_error("rtl: a result without a request");
      readPort(top_->res_data_o, resWire.data(), kResWords);
      fx::unpackResult(resWire, results.emplace_back());
      ++taken;
    }
    if (offering && !reqFire) ++stats.inputStalls;
    const uint64_t edge = cycle_;
    tick();
    checkAssertions();
    if (reqFire) {
      offering = false;
      ++offered;
      ++stats.requests;
    }
    if (reqFire || resFire) lastProgress = cycle_;
    if (taken == n) stats.cycles = edge - firstCycle + 1;
    if (cycle_ - lastProgress > kWatchdog) {
      throw std::runtime_error(fmt::format(
          "rtl: no progress for {} cycles ({} of {} requests accepted, {} results taken)",
          kWatchdog, stats.requests, n, taken));
    }
  }
  top_->req_valid_i = 0;
  top_->res_ready_i = 0;
  top_->eval();
  if (wave_) {
    wave_->dump(2 * cycle_);
    wave_->close();
    wave_.reset();
  }

  stats.results = taken;
  return stats;
}

}  // namespace lancer
