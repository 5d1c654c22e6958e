// libFuzzer target: Lancer's PLY reader (sw/scene/ply.h, readPly), ASCII and
// binary. The input is a PLY file; readPly accepts it or throws InputError
// naming the file, never reading past its end or allocating for counts the
// file cannot hold. An accepted scene passes checkScene (fuzz_scene_checks.h).

#include <cstring>
#include <string_view>

#include "common/error.h"
#include "fuzz_scene_checks.h"
#include "scene/ply.h"

using namespace lancer;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Scene scene;
  try {
    scene = readPly(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.ply");
  } catch (const InputError& e) {
    FUZZ_CHECK(std::strncmp(e.what(), "fuzz.ply", 8) == 0, "error does not name the file: {}", e.what());
    return 0;
  }
  fuzz::checkScene(scene);
  return 0;
}
