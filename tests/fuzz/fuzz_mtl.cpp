// libFuzzer target: Lancer's MTL reader (sw/scene/obj.h, readMtl) and the
// Whitted terms it makes. The input is an MTL file; readMtl accepts it or
// throws InputError naming the file. Every material it accepts has finite
// terms in range (fuzz_scene_checks.h), which the tracers rely on. (Before
// Lancer had its own reader this target ran assimp's MTL parser, and found
// the two crashes its corpus keeps: corpus/mtl/assimp_segv_*.)

#include <cstring>
#include <string_view>

#include "common/error.h"
#include "fuzz_scene_checks.h"
#include "scene/obj.h"

using namespace lancer;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<Material> materials;
  try {
    materials = readMtl(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.mtl");
  } catch (const InputError& e) {
    FUZZ_CHECK(std::strncmp(e.what(), "fuzz.mtl", 8) == 0, "error does not name the file: {}", e.what());
    return 0;
  }
  for (size_t i = 0; i < materials.size(); ++i) fuzz::checkMaterial(materials[i], i);
  return 0;
}
