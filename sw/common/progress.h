#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace lancer {

// A one-line progress bar on stderr, drawn only when stderr is a terminal (so
// logs and pipes stay clean). Thread-compatible: call advance() from one thread.
class Progress {
 public:
  Progress(std::string label, uint64_t total);
  ~Progress();
  void advance(uint64_t n = 1);
  void finish();

 private:
  void draw(bool force);

  std::string label_;
  uint64_t total_;
  uint64_t done_ = 0;
  bool enabled_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_, lastDraw_;
};

}  // namespace lancer
