// libFuzzer target: the NFF reader (sw/scene/nff). Arbitrary bytes are an NFF
// file; the reader accepts them or throws InputError naming the file. A scene
// it accepts passes checkScene (fuzz_scene_checks.h): finite geometry inside
// its bounds, a valid material for every triangle, materials in range.

#include <cstring>
#include <sstream>

#include "common/error.h"
#include "fuzz_scene_checks.h"
#include "scene/nff.h"

using namespace lancer;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  // Coarse tessellations keep a run quick; the code paths are the same.
  const NffOptions options{.sphereDivisions = 2, .coneSlices = 4};
  Scene scene;
  try {
    scene = readNff(in, "fuzz.nff", options);
  } catch (const InputError& e) {
    FUZZ_CHECK(std::strstr(e.what(), "fuzz.nff") != nullptr, "error does not name the file: {}", e.what());
    return 0;
  }
  fuzz::checkScene(scene);
  return 0;
}
