// lancer convert --scene IN --out OUT.obj|.ply|.glb: writes the scene as
// Lancer read it (every coordinate exact, the triangles in id order), so that
// reading OUT gives the same floats (sw/scene/write.h, docs/scenes.md).
#include <fmt/format.h>

#include "cli/options.h"
#include "scene/write.h"

namespace lancer::cli {

void addConvertCommand(CLI::App& app) {
  struct Args {
    SceneOptions scene;
    std::string out;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = app.add_subcommand(
      "convert", fmt::format("Write the scene as Lancer read it, every coordinate exact: {}", kWrittenFormats));
  args->scene.quadrics = QuadricForm::Tessellate;  // the formats written hold triangles
  args->scene.add(*cmd);
  cmd->add_option("--out", args->out, fmt::format("Output file: {}", kWrittenFormats))->required();
  cmd->callback([args] {
    const Scene scene = args->scene.load();
    writeScene(scene, args->out);
    fmt::print("convert: {} ({} triangles, {} materials, {} lights, scene_numbers {}) -> {}\n", scene.name, scene.size(),
               scene.materials.size(), scene.lights.size(), toString(scene.numbers), args->out);
  });
}

}  // namespace lancer::cli
