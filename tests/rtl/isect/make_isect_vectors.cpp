// Writes test vectors for the Icarus bench tests/rtl/isect/tb_rt_isect.sv:
// the hard cases (isect_cases.h) and random pairs, each with the golden result.
// Three $readmemh files, one record per line in hex, most significant digit
// first, in the order of the requests:
//   PREFIX.ray.hex  rt_pkg::isect_ray_t   PREFIX.tri.hex  rt_pkg::isect_tri_t
//   PREFIX.res.hex  rt_pkg::isect_res_t (expected)
// and PREFIX.count with the number of vectors.
// Usage: make_isect_vectors PREFIX [RANDOM_PAIRS] [MAX_HARD_CASES]
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include <fmt/format.h>

#include "golden/isect.h"
#include "isect/isect_cases.h"

namespace {

// A record as hex digits: exactly ceil(bits/4) of them, MSB first.
std::string hexDigits(const lancer::fx::Wire& wire, int bits) {
  std::string s;
  for (int digit = (bits + 3) / 4 - 1; digit >= 0; --digit) {
    const uint32_t nibble = (wire[size_t(digit / 8)] >> (4 * (digit % 8))) & 0xf;
    s += "0123456789abcdef"[nibble];
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lancer;
  if (argc < 2) {
    std::cerr << "usage: make_isect_vectors PREFIX [RANDOM_PAIRS] [MAX_HARD_CASES]\n";
    return 2;
  }
  const std::string prefix = argv[1];
  const size_t randomCount = argc > 2 ? size_t(std::stoull(argv[2])) : 1000;
  const size_t maxHard = argc > 3 ? size_t(std::stoull(argv[3])) : size_t(-1);

  // The hard cases, thinned evenly to at most maxHard, then random pairs.
  const auto hard = rtltest::allHardCases(3);
  std::vector<IsectRequest> requests;
  const size_t stride = hard.size() > maxHard ? (hard.size() + maxHard - 1) / maxHard : 1;
  for (size_t i = 0; i < hard.size(); i += stride) requests.push_back(hard[i]);
  const auto random = rtltest::randomPairs(randomCount, 4);
  requests.insert(requests.end(), random.begin(), random.end());

  std::ofstream ray(prefix + ".ray.hex"), tri(prefix + ".tri.hex"), res(prefix + ".res.hex");
  size_t hits = 0;
  for (size_t i = 0; i < requests.size(); ++i) {
    IsectRequest r = requests[i];
    r.ray.id = uint32_t(i);  // the bench reports mismatches by ray id = vector index
    const fx::IsectResult expected = fx::intersect(r.ray, r.tri);
    hits += expected.hit;
    ray << hexDigits(fx::packWire(r.ray), fx::kIsectRayBits) << '\n';
    tri << hexDigits(fx::packWire(r.tri), fx::kIsectTriBits) << '\n';
    res << hexDigits(fx::packWire(expected), fx::kIsectResBits) << '\n';
  }
  std::ofstream(prefix + ".count") << requests.size() << '\n';
  if (!ray || !tri || !res) {
    std::cerr << "make_isect_vectors: cannot write " << prefix << ".*.hex\n";
    return 1;
  }
  std::cout << fmt::format("{} vectors ({} hard, {} random, {} hits) -> {}.*.hex\n",
                           requests.size(), requests.size() - random.size(), random.size(), hits,
                           prefix);
  return 0;
}
