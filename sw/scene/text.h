#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lancer {

// Numbers and lines of the text formats Lancer reads itself (OBJ, MTL, PLY,
// STL, NFF; docs/scenes.md, "Numbers").

// A decimal number as the float nearest to it, ties to even: std::from_chars
// straight to float, never through double, where a decimal close to the
// midpoint of two floats can round to the midpoint and then to the wrong side
// of it. Takes an optional sign, digits with an optional point and exponent,
// "inf" and "nan", and nothing else (no spaces, no hex). Beyond float range it
// reads as an infinity, below half the smallest subnormal as a zero, as strtof
// does. nullopt: not a number.
std::optional<float> parseFloat(std::string_view text);

// A whole decimal number with an optional sign; nullopt if it is not one or
// does not fit.
std::optional<int64_t> parseInteger(std::string_view text);

// The whole of a file. Throws InputError "<path>: cannot open file".
std::string readFileBytes(const std::string& path);

// The line (from 1) of the first NUL byte in `text`, or 0 if it has none. No
// text format has one (a UTF-16 file has many).
size_t lineOfNulByte(std::string_view text);

// Space, tab, vertical tab and form feed: what separates the words of a line.
inline bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }

// `text` in lower case (ASCII): keywords and extensions that writers spell in
// either case.
std::string lowercase(std::string_view text);

// `text` without blanks at either end.
std::string_view trimmed(std::string_view text);

// The blank-separated words of a line, into `words` (cleared first).
void splitWords(std::string_view line, std::vector<std::string_view>& words);

// The statements of a line-oriented format (OBJ, MTL, ASCII STL): lines end at
// \n, \r\n or a lone \r; with `continuation` (OBJ, MTL), a line whose last
// character is a backslash goes on with the next line (joined with a space); a
// UTF-8 byte-order mark at the start is skipped.
class TextLines {
 public:
  explicit TextLines(std::string_view text, bool continuation = true);
  // The next line, continuations joined, without its line end; nullopt at
  // the end. Valid until the next call.
  std::optional<std::string_view> next();
  // The line (from 1) on which the line last returned starts.
  size_t number() const { return number_; }

 private:
  std::string_view rawLine();  // the next physical line; advances next_, counts it

  std::string_view text_;
  bool continuation_;
  size_t at_ = 0;
  size_t number_ = 0, next_ = 1;  // the last line returned; the next physical line
  std::string joined_;
};

}  // namespace lancer
