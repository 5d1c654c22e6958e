#include "driver/wave_file.h"

#include <filesystem>
#include <map>
#include <mutex>

namespace lancer {

std::string nextWaveFile(const std::string& path) {
  static std::mutex mutex;
  static std::map<std::string, int> opened;
  if (path.empty()) return path;
  const std::lock_guard lock(mutex);
  const int n = opened[path]++;
  if (n == 0) return path;
  std::filesystem::path p(path);
  const std::string ext = p.extension().string();
  p.replace_extension();
  return p.string() + "." + std::to_string(n) + ext;
}

}  // namespace lancer
