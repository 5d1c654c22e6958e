#pragma once

// What the libFuzzer targets of tests/fuzz share: a property check that stops
// the run with a message (libFuzzer saves the input as a crash reproducer),
// a reader of typed values from the input bytes, and a per-process file for
// the parsers that read paths.

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>

// A property of the code under test that must hold for every input.
#define FUZZ_CHECK(cond, ...)                                                                          \
  do {                                                                                                 \
    if (!(cond)) {                                                                                     \
      std::fprintf(stderr, "fuzz property failed at %s:%d: %s\n  %s\n", __FILE__, __LINE__, #cond,   \
                   fmt::format(__VA_ARGS__).c_str());                                                  \
      std::abort();                                                                                    \
    }                                                                                                  \
  } while (0)

namespace lancer::fuzz {

// Reads fixed-size values off the front of the input; zeros once it runs out.
class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  template <class T>
  T take() {
    T value{};
    const size_t n = std::min(sizeof(T), size_);
    std::memcpy(&value, data_, n);
    data_ += n;
    size_ -= n;
    return value;
  }
  size_t left() const { return size_; }
  const uint8_t* rest() const { return data_; }

 private:
  const uint8_t* data_;
  size_t size_;
};

// A file of this process in the temporary directory, e.g. for readRaysFile.
inline std::filesystem::path tempPath(const std::string& name) {
  return std::filesystem::temp_directory_path() / fmt::format("lancer-fuzz-{}-{}", ::getpid(), name);
}

inline void writeFile(const std::filesystem::path& path, const void* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), std::streamsize(size));
  FUZZ_CHECK(out.good(), "cannot write {}", path.string());
}

}  // namespace lancer::fuzz
