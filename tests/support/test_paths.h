#pragma once

#include <string>

// Scenes the tests use. The bunny comes from scripts/deps; Wuson from Debian's
// assimp-testmodels. Both are required: a missing file fails the test loudly.
namespace lancer::test {
inline const std::string kBunny = std::string(LANCER_DATA_DIR) + "/scenes/bunny.obj";
inline const std::string kWuson = std::string(LANCER_ASSIMP_MODELS) + "/OBJ/WusonOBJ.obj";
inline const std::string kAssimpModels = LANCER_ASSIMP_MODELS;
}  // namespace lancer::test
