#include "common/progress.h"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace lancer {

Progress::Progress(std::string label, uint64_t total)
    : label_(std::move(label)), total_(total), enabled_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()), lastDraw_(start_) {}

Progress::~Progress() { finish(); }

void Progress::advance(uint64_t n) {
  done_ += n;
  draw(false);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (!enabled_) return;
  draw(true);
  std::fputc('\n', stderr);
}

void Progress::draw(bool force) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  lastDraw_ = now;
  const double fraction = total_ ? double(done_) / double(total_) : 1.0;
  constexpr int kWidth = 30;
  const int filled = int(fraction * kWidth);
  const double seconds = std::chrono::duration<double>(now - start_).count();
  std::fputs(fmt::format("\r{} [{}{}] {:5.1f}% {}/{} {:.1f}s", label_, std::string(filled, '#'),
                         std::string(kWidth - filled, '.'), 100.0 * fraction, done_, total_, seconds)
                 .c_str(),
             stderr);
  std::fflush(stderr);
}

}  // namespace lancer
