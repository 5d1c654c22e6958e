// libFuzzer target: the rays-file parser (sw/scene/rays_file). Arbitrary bytes
// are a rays file; the parser accepts them or throws InputError. A file it
// accepts holds only valid rays (finite, non-zero direction), and written back
// with writeRaysFile and read again gives the same rays bit for bit.

#include <cstring>

#include "common/error.h"
#include "fuzz_support.h"
#include "scene/rays_file.h"

using namespace lancer;

namespace {

bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string in = fuzz::tempPath("in.rays").string();
  static const std::string out = fuzz::tempPath("out.rays").string();
  fuzz::writeFile(in, data, size);
  std::vector<Ray> rays;
  try {
    rays = readRaysFile(in);
  } catch (const InputError& e) {
    FUZZ_CHECK(std::strstr(e.what(), in.c_str()) != nullptr, "error does not name the file: {}", e.what());
    return 0;
  }
  size_t lines = 1;
  for (size_t i = 0; i < size; ++i) lines += data[i] == '\n';
  FUZZ_CHECK(rays.size() <= lines, "{} rays from {} lines", rays.size(), lines);
  for (size_t i = 0; i < rays.size(); ++i) {
    validateRay(rays[i], i, "accepted ray");  // throws (and the run fails) if the parser let one through
  }
  writeRaysFile(out, rays, "fuzz round trip");
  const std::vector<Ray> again = readRaysFile(out);
  FUZZ_CHECK(again.size() == rays.size(), "{} rays written, {} read back", rays.size(), again.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    FUZZ_CHECK(sameBits(rays[i].origin, again[i].origin) && sameBits(rays[i].dir, again[i].dir),
               "ray {} changed on the round trip", i);
  }
  return 0;
}
