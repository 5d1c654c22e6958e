// libFuzzer target: the MTL side of the OBJ loader (sw/scene/scene.cpp, assimp's
// MTL parser and readWhittedTerms). The input is the .mtl file of a fixed
// two-triangle OBJ that uses materials "m" and "n"; loadScene accepts it or
// throws InputError naming the file. An accepted scene passes checkScene
// (fuzz_scene_checks.h): every material's Whitted terms are finite and in range.

#include <cstring>

#include "common/error.h"
#include "fuzz_scene_checks.h"

using namespace lancer;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::filesystem::path obj = fuzz::tempPath("scene.obj");
  static const std::filesystem::path mtl = fuzz::tempPath("scene.mtl");
  static const bool written = [] {
    const std::string text = fmt::format(
        "mtllib {}\n"
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
        "usemtl m\nf 1 2 3\n"
        "usemtl n\nf 1 3 4\n",
        mtl.filename().string());
    fuzz::writeFile(obj, text.data(), text.size());
    return true;
  }();
  (void)written;
  fuzz::writeFile(mtl, data, size);
  Scene scene;
  try {
    scene = loadScene(obj.string());
  } catch (const InputError& e) {
    FUZZ_CHECK(std::strstr(e.what(), obj.string().c_str()) != nullptr, "error does not name the file: {}",
               e.what());
    return 0;
  }
  fuzz::checkScene(scene);
  return 0;
}
