#include "scene/text.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "common/error.h"

namespace lancer {

namespace {

// from_chars takes no '+'; writers may put one. Returns false for a sign after it.
bool dropPlus(std::string_view& text) {
  if (!text.starts_with('+')) return true;
  text.remove_prefix(1);
  return !text.starts_with('+') && !text.starts_with('-');
}

}  // namespace

std::optional<float> parseFloat(std::string_view text) {
  if (!dropPlus(text)) return std::nullopt;
  const char* end = text.data() + text.size();
  float value = 0.0f;
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ptr != end || text.empty()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) {
    // libstdc++ leaves `value` alone when the number is out of range. The text
    // is a well-formed number, so strtof (correctly rounded in glibc) gives its
    // float: a signed infinity beyond the range, a signed zero below it.
    return std::strtof(std::string(text).c_str(), nullptr);
  }
  if (ec != std::errc()) return std::nullopt;
  return value;
}

std::optional<int64_t> parseInteger(std::string_view text) {
  if (!dropPlus(text)) return std::nullopt;
  const char* end = text.data() + text.size();
  int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || text.empty()) return std::nullopt;
  return value;
}

std::string readFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open file", path));
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("{}: read error", path));
  return std::move(bytes).str();
}

size_t lineOfNulByte(std::string_view text) {
  const size_t at = text.find('\0');
  if (at == std::string_view::npos) return 0;
  return 1 + size_t(std::count(text.begin(), text.begin() + long(at), '\n'));
}

std::string lowercase(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return out;
}

std::string_view trimmed(std::string_view text) {
  while (!text.empty() && isBlank(text.front())) text.remove_prefix(1);
  while (!text.empty() && isBlank(text.back())) text.remove_suffix(1);
  return text;
}

void splitWords(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && isBlank(line[i])) ++i;
    const size_t start = i;
    while (i < line.size() && !isBlank(line[i])) ++i;
    if (i > start) words.push_back(line.substr(start, i - start));
  }
}

TextLines::TextLines(std::string_view text, bool continuation) : text_(text), continuation_(continuation) {
  if (text_.starts_with("\xEF\xBB\xBF")) at_ = 3;
}

std::string_view TextLines::rawLine() {
  const size_t end = std::min(text_.find_first_of("\r\n", at_), text_.size());
  const std::string_view line = text_.substr(at_, end - at_);
  at_ = end;
  if (at_ < text_.size()) at_ += text_.compare(at_, 2, "\r\n") == 0 ? 2 : 1;
  ++next_;
  return line;
}

std::optional<std::string_view> TextLines::next() {
  if (at_ >= text_.size()) return std::nullopt;
  number_ = next_;
  std::string_view line = rawLine();
  if (!continuation_ || !line.ends_with('\\')) return line;
  joined_.assign(line.substr(0, line.size() - 1));
  while (at_ < text_.size()) {
    joined_ += ' ';
    line = rawLine();
    if (!line.ends_with('\\')) {
      joined_ += line;
      return joined_;
    }
    joined_.append(line.substr(0, line.size() - 1));
  }
  return joined_;  // a backslash on the file's last line continues nothing
}

}  // namespace lancer
