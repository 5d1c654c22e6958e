#pragma once

// The run loop of rt_isect's request and result streams, over any clocked
// model whose ports are plain members under the RTL's names:
//   VerilatedUnit<Vrt_isect>           (verilated_unit.h)  the Verilated RTL, "rtl"
//   ModelUnit<sc::rt_isect_model>      (model_unit.h)      the SystemC cycle model
//                                                          on value ports, "systemc"
// (A Clocked's members: traversal_run.h.)
//
// Requests are offered in order (the producer idles with
// StreamOptions::inputIdleProbability when it has nothing on offer and holds
// an offered request until it is taken); the consumer deasserts res_ready_i
// with StreamOptions::outputStallProbability; both draw from one
// std::mt19937_64 seeded with StreamOptions::seed, the idle draw before the
// stall draw, as rt_pipe_tb draws in the SystemC kernel. So every
// cycle-accurate model sees the same stimulus for the same options.

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <random>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "driver/isect_device.h"
#include "driver/verilated_port.h"
#include "driver/wave_file.h"
#include "golden/quadric.h"
#include "golden/records.h"
#include "golden/stimulus.h"
#include "isect/rt_isect_cycle.h"

namespace lancer {

namespace isect_detail {

// Nothing offered, nothing taken.
template <class Top>
void idleInputs(Top& top) {
  top.req_valid_i = 0;
  top.res_ready_i = 0;
}

// The primitive of a request, and the port it enters by: rt_isect's triangle
// (req_tri_i), rt_quadric's record (req_quadric_i).
inline const fx::QTriangle& primitiveOf(const IsectRequest& req) { return req.tri; }
inline const fx::QQuadric& primitiveOf(const QuadricRequest& req) { return req.quadric; }

template <class Top>
void writePrimitive(Top& top, const fx::QTriangle& tri) {
  using Port = std::remove_reference_t<decltype(top.req_tri_i)>;
  static_assert(portWords<Port>() >= fx::kIsectTriWords && portWords<Port>() < fx::kIsectTriWords + 2,
                "req_tri_i does not match fx::kIsectTriBits: rebuild rt_pkg");
  fx::TriWire wire;
  fx::packWire(tri, wire);
  writePort(top.req_tri_i, wire.data(), wire.size());
}

template <class Top>
void writePrimitive(Top& top, const fx::QQuadric& quadric) {
  constexpr size_t kWords = size_t(fx::wireWords(fx::kIsectQuadricBits));
  using Port = std::remove_reference_t<decltype(top.req_quadric_i)>;
  static_assert(portWords<Port>() >= kWords && portWords<Port>() < kWords + 2,
                "req_quadric_i does not match fx::kIsectQuadricBits: rebuild rt_pkg");
  std::array<uint32_t, kWords> wire;
  fx::packWire(quadric, wire);
  writePort(top.req_quadric_i, wire.data(), kWords);
}

}  // namespace isect_detail

// The quadric pipeline's waveforms sit beside the triangles': x.fst gives
// x.quadric.fst (then x.quadric.1.fst, ...), so that each file holds one module.
inline StreamOptions quadricWaves(const StreamOptions& options) {
  if (options.wavePath.empty()) return options;
  StreamOptions out = options;
  std::filesystem::path p(options.wavePath);
  const std::string ext = p.extension().string();
  p.replace_extension();
  out.wavePath = p.string() + ".quadric" + ext;
  return out;
}

// Without a transfer for this long the model has lost a request or a result
// (a stalled stream moves every 1 / (1 - p) cycles: 10^4 at p = 0.9999).
// Stall or idle probabilities of 1 never move, and end here.
inline constexpr uint64_t kIsectWatchdogCycles = 1000000;

// Streams `requests` through the model, appending the results in delivery
// order. The model is not reset: a finished run leaves every stage empty. The
// StreamStats cycles run from the first cycle a request is offered to the
// cycle the last result is taken. With `trace`, the ports of every cycle of
// the run are appended to it (cycle 0: the run's first), as rt_pipe_tb
// samples them. Throws std::runtime_error naming Clocked::kModel when the
// stream stops (watchdog) or a result comes without a request.
template <class Clocked, class Request>
StreamStats runIsectStream(Clocked& unit, std::span<const Request> requests,
                           std::vector<fx::IsectResult>& results, const StreamOptions& options,
                           std::vector<sc::IsectCycle>* trace = nullptr) {
  using Top = typename Clocked::top_type;
  constexpr size_t kRayWords = fx::kIsectRayWords;
  constexpr size_t kResWords = fx::kIsectResWords;
  using RayPort = std::remove_reference_t<decltype(std::declval<Top&>().req_ray_i)>;
  using ResPort = std::remove_reference_t<decltype(std::declval<Top&>().res_data_o)>;
  using Primitive = std::remove_cvref_t<decltype(isect_detail::primitiveOf(std::declval<const Request&>()))>;
  static_assert(portWords<RayPort>() >= kRayWords && portWords<RayPort>() < kRayWords + 2,
                "req_ray_i does not match fx::kIsectRayBits: rebuild rt_pkg");
  static_assert(portWords<ResPort>() >= kResWords && portWords<ResPort>() < kResWords + 2,
                "res_data_o does not match fx::kIsectResBits: rebuild rt_pkg");

  StreamStats stats;
  const size_t n = requests.size();
  if (n == 0) return stats;

  // Records are packed when offered and unpacked when taken, straight from and
  // into the ports: no image of the whole stream is kept. A port keeps its
  // value, so a ray (or primitive) equal to the previous request's is not
  // packed again: streams of one ray against its candidate triangles pay once.
  if (results.capacity() < results.size() + n) {
    results.reserve(std::max(results.size() + n, 2 * results.capacity()));
  }
  fx::RayWire rayWire;  // fixed-size images: packing allocates nothing
  fx::ResWire resWire;
  const fx::QRay* portRay = nullptr;
  const Primitive* portPrimitive = nullptr;

  Top& top = unit.top();
  unit.select();  // a run does not reset the model: select its context here
  unit.openWave(nextWaveFile(options.wavePath));

  std::mt19937_64 rng(options.seed);
  fx::Coin idle(options.inputIdleProbability, rng);
  fx::Coin stall(options.outputStallProbability, rng);

  size_t offered = 0;  // index of the request on offer, or of the next one
  bool offering = false;
  size_t taken = 0;
  uint64_t cycle = 0;  // of this run
  uint64_t firstCycle = 0, lastProgress = 0;
  bool started = false;

  try {
    while (taken < n) {
      // Producer: offers the next request, unless idling; keeps an offer until taken.
      if (!offering && offered < n && !idle()) {
        const Request& req = requests[offered];
        if (!portRay || !(req.ray == *portRay)) {
          fx::packWire(req.ray, rayWire);
          writePort(top.req_ray_i, rayWire.data(), kRayWords);
          portRay = &req.ray;
        }
        const Primitive& primitive = isect_detail::primitiveOf(req);
        if (!portPrimitive || !(primitive == *portPrimitive)) {
          isect_detail::writePrimitive(top, primitive);
          portPrimitive = &primitive;
        }
        offering = true;
        if (!started) {
          started = true;
          firstCycle = cycle;
        }
      }
      top.req_valid_i = offering;
      // Consumer: ready unless stalling.
      const bool ready = !stall();
      top.res_ready_i = ready;
      unit.settle();  // req_ready_o depends on res_ready_i

      const bool reqFire = offering && top.req_ready_o;
      const bool resFire = top.res_valid_o && ready;
      if (trace) {
        sc::IsectCycle& c = trace->emplace_back();
        c.cycle = cycle;
        c.reqValid = offering;
        c.reqReady = top.req_ready_o;
        c.resValid = top.res_valid_o;
        c.resReady = ready;
        if (c.resValid) {
          c.resData.resize(kResWords);
          readPort(top.res_data_o, c.resData.data(), kResWords);
        }
      }
      if (resFire) {
        if (taken >= stats.requests) {
          throw std::runtime_error(fmt::format("{}: a result without a request", Clocked::kModel));
        }
        readPort(top.res_data_o, resWire.data(), kResWords);
        fx::unpackResult(resWire, results.emplace_back());
        ++taken;
      }
      if (offering && !reqFire) ++stats.inputStalls;
      unit.tick();
      if (reqFire) {
        offering = false;
        ++offered;
        ++stats.requests;
      }
      if (taken == n) stats.cycles = cycle - firstCycle + 1;
      ++cycle;
      if (reqFire || resFire) lastProgress = cycle;
      if (cycle - lastProgress > kIsectWatchdogCycles) {
        throw std::runtime_error(
            fmt::format("{}: no progress for {} cycles ({} of {} requests accepted, {} results taken)",
                        Clocked::kModel, kIsectWatchdogCycles, stats.requests, n, taken));
      }
    }
  } catch (...) {
    unit.closeWave();
    throw;
  }
  isect_detail::idleInputs(top);
  unit.settle();
  unit.closeWave();

  stats.results = taken;
  return stats;
}

}  // namespace lancer
