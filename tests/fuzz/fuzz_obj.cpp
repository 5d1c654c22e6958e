// libFuzzer target: Lancer's OBJ reader (sw/scene/obj.h, readObj). The input
// is an OBJ file, read in an empty folder (an mtllib names no file there, so
// the MTL side is fuzz_mtl's); readObj accepts it or throws InputError naming
// the file. An accepted scene passes checkScene (fuzz_scene_checks.h): a
// material per triangle, finite vertices inside its bounds, shading normals
// none or one set a triangle, all finite.

#include <cstring>
#include <string_view>

#include "common/error.h"
#include "fuzz_scene_checks.h"
#include "scene/obj.h"

using namespace lancer;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path folder = [] {
    const std::filesystem::path dir = fuzz::tempPath("obj");
    std::filesystem::create_directories(dir);
    return dir;
  }();
  Scene scene;
  try {
    scene = readObj(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.obj", folder);
  } catch (const InputError& e) {
    FUZZ_CHECK(std::strncmp(e.what(), "fuzz.obj", 8) == 0, "error does not name the file: {}", e.what());
    return 0;
  }
  fuzz::checkScene(scene);
  return 0;
}
