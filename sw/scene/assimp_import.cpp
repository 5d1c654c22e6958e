#include "scene/assimp_import.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <new>

#include <sys/resource.h>
#include <unistd.h>

#include <fmt/format.h>

#include "common/error.h"

namespace lancer {

namespace {

// Caps the address space while assimp parses, so a file that declares absurd
// counts (assimp's invalid/OutOfMemory.off claims trillions of vertices) fails
// with bad_alloc instead of being killed by the kernel. Restored on scope exit.
class AddressSpaceCap {
 public:
  explicit AddressSpaceCap(uint64_t fileBytes) {
    if (getrlimit(RLIMIT_AS, &saved_) != 0) return;
    long pages = 0, pageSize = sysconf(_SC_PAGESIZE);
    if (std::ifstream statm("/proc/self/statm"); !(statm >> pages)) return;
    // Generous: assimp's in-memory scene is a few hundred bytes per input byte at worst.
    const uint64_t budget = std::max<uint64_t>(uint64_t(4) << 30, fileBytes * 256);
    rlimit capped = saved_;
    capped.rlim_cur = std::min<uint64_t>(saved_.rlim_cur, uint64_t(pages) * uint64_t(pageSize) + budget);
    active_ = setrlimit(RLIMIT_AS, &capped) == 0;
  }
  ~AddressSpaceCap() {
    if (active_) setrlimit(RLIMIT_AS, &saved_);
  }

 private:
  rlimit saved_{};
  bool active_ = false;
};

}  // namespace

const aiScene* importWithAssimp(Assimp::Importer& importer, const std::string& path, unsigned flags) {
  std::error_code sizeError;
  const uint64_t fileBytes = std::filesystem::file_size(path, sizeError);
  if (sizeError) throw InputError(fmt::format("{}: cannot open file", path));
  const aiScene* ai = nullptr;
  try {
    AddressSpaceCap cap(fileBytes);
    ai = importer.ReadFile(path, flags);
  } catch (const std::bad_alloc&) {
    throw InputError(fmt::format("{}: cannot read scene: it declares more data than fits in memory", path));
  } catch (const std::exception& e) {
    // assimp catches its own errors; a library it calls may not.
    throw InputError(fmt::format("{}: cannot read scene: {}", path, e.what()));
  }
  if (!ai || !ai->mRootNode) {
    std::string reason = importer.GetErrorString();
    std::replace(reason.begin(), reason.end(), '\n', ' ');
    throw InputError(fmt::format("{}: cannot read scene: {}", path, reason.empty() ? "assimp read no scene" : reason));
  }
  return ai;
}

}  // namespace lancer
