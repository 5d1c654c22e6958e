// libFuzzer target: the rays-file parser (sw/scene/rays_file). Arbitrary bytes
// are a rays file; the parser accepts them or throws InputError naming the
// file. A file it accepts holds only valid rays (finite, non-zero direction),
// at most one a line, no NUL byte outside comments; written back with
// writeRays and read again, it gives the same rays bit for bit.

#include <cstring>
#include <sstream>
#include <string_view>

#include "common/error.h"
#include "fuzz_support.h"
#include "scene/rays_file.h"

using namespace lancer;

namespace {

bool sameBits(const glm::vec3& a, const glm::vec3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Lines (split at '\n'), and whether any has a NUL before its comment.
std::pair<size_t, bool> scanLines(std::string_view text) {
  size_t lines = 0;
  bool nul = false;
  for (size_t at = 0; at <= text.size(); ++lines) {
    const size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view line = text.substr(at, std::min(text.find('#', at), end) - at);
    nul |= line.find('\0') != std::string_view::npos;
    at = end + 1;
  }
  return {lines, nul};
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::istringstream in(text);
  std::vector<Ray> rays;
  try {
    rays = readRays(in, "fuzz.rays");
  } catch (const InputError& e) {
    FUZZ_CHECK(std::strncmp(e.what(), "fuzz.rays", 9) == 0, "error does not name the file: {}", e.what());
    return 0;
  }
  const auto [lines, nul] = scanLines(text);
  FUZZ_CHECK(rays.size() <= lines, "{} rays from {} lines", rays.size(), lines);
  FUZZ_CHECK(!nul, "a NUL byte in a ray line was accepted (and the rest of its line dropped)");
  for (size_t i = 0; i < rays.size(); ++i) {
    validateRay(rays[i], i, "accepted ray");  // throws (and the run fails) if the parser let one through
  }
  std::ostringstream out;
  writeRays(out, rays, "fuzz round trip\n0 0 0 1 1 1");  // a comment line must not become a ray
  std::istringstream back(out.str());
  const std::vector<Ray> again = readRays(back, "round trip");
  FUZZ_CHECK(again.size() == rays.size(), "{} rays written, {} read back", rays.size(), again.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    FUZZ_CHECK(sameBits(rays[i].origin, again[i].origin) && sameBits(rays[i].dir, again[i].dir),
               "ray {} changed on the round trip", i);
  }
  return 0;
}
