// The numbers of Lancer's text readers (sw/scene/text.h): every decimal read
// as the float nearest to it, ties to even, bit for bit what glibc's strtof
// (correctly rounded) gives, at the ends of float's range and at halfway points.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>

#include <fmt/format.h>

#include "scene/text.h"
#include "text_cases.h"

namespace lancer {
namespace {

uint32_t bitsOf(float f) { return std::bit_cast<uint32_t>(f); }

// parseFloat(text) has strtof(text)'s bits.
void expectStrtof(const std::string& text) {
  const std::optional<float> got = parseFloat(text);
  ASSERT_TRUE(got.has_value()) << text;
  const float want = std::strtof(text.c_str(), nullptr);
  EXPECT_EQ(bitsOf(*got), bitsOf(want)) << text << ": got " << fmt::format("{:a}", *got) << ", strtof "
                                        << fmt::format("{:a}", want);
}

TEST(Numbers, ExtremeExponentsAreStrtofBitForBit) {
  for (const std::string& text : test::kExtremeDecimals) expectStrtof(text);
  // Beyond the range: infinities and signed zeros, as strtof.
  for (const char* text : {"1e39", "-1e39", "3.5e38", "1e-50", "-1e-50", "7e-46", "1e-400"}) expectStrtof(text);
  EXPECT_EQ(*parseFloat("1e-45"), std::ldexp(1.0f, -149));  // the smallest subnormal
  EXPECT_EQ(*parseFloat("3.4028235e38"), std::numeric_limits<float>::max());
  EXPECT_TRUE(std::signbit(*parseFloat("-1e-50")));
}

// The midpoint of two adjacent floats rounds to the even one; a hair above or
// below it, to the nearer one. The hair is far below a double's precision: a
// reader that goes through double lands on the midpoint and rounds it to even,
// the wrong float for the decimal above it.
TEST(Numbers, HalfwayCasesRoundToEven) {
  for (const test::Halfway& h : test::kHalfwayDecimals) {
    SCOPED_TRACE(h.text);
    const std::optional<float> got = parseFloat(h.text);
    ASSERT_TRUE(got.has_value());
    EXPECT_EQ(fmt::format("{:a}", *got), h.nearest);
    expectStrtof(h.text);
  }
  // The double-rounding trap is real: through double, the decimal just above
  // the midpoint between 1 and 1 + 2^-23 reads as 1.
  const char* above = "1.0000000596046447753906250000001";
  EXPECT_EQ(float(std::strtod(above, nullptr)), 1.0f);
  EXPECT_EQ(*parseFloat(above), 1.0f + 0x1p-23f);
}

TEST(Numbers, TheIssuesCoordinate) {
  // assimp 5.2 read it as 0x1.590002p-32 (issue 21).
  EXPECT_EQ(fmt::format("{:a}", *parseFloat("3.1377567211166024e-10")), "0x1.59p-32");
}

// Random decimals near the midpoints of random floats, normal and subnormal,
// and full-precision doubles, against strtof.
TEST(Numbers, RandomDecimalsNearMidpointsAreStrtof) {
  std::mt19937_64 rng(21);
  for (int i = 0; i < 20000; ++i) {
    const int exponent = int(rng() % 280) - 150;  // down into the subnormals
    const float f = std::ldexp(1.0f + float(rng() >> 41) * 0x1p-23f, exponent);
    const double mid = (double(f) + double(std::nextafter(f, INFINITY))) / 2;
    const int digits = 6 + int(rng() % 30);
    const double nudge = (i % 3 - 1) * 1e-13;  // below, at, above the midpoint
    expectStrtof(fmt::format("{:.{}e}", mid * (1 + nudge), digits));
    expectStrtof(fmt::format("{:.17g}", std::ldexp(double(rng() >> 11) * 0x1p-53 + 0.5, exponent)));
  }
}

TEST(Numbers, WhatIsNotANumber) {
  for (const char* text : {"", "+", "-", "1e", "1,5", "0x1p3", " 1", "1 ", "--1", "+-1", "++1", "1.5.2", "e5", "."}) {
    EXPECT_FALSE(parseFloat(text).has_value()) << "'" << text << "'";
  }
  EXPECT_EQ(*parseFloat("+1"), 1.0f);
  EXPECT_EQ(*parseFloat("2."), 2.0f);
  EXPECT_EQ(*parseFloat(".5"), 0.5f);
  EXPECT_TRUE(std::signbit(*parseFloat("-0")));
  EXPECT_TRUE(std::isinf(*parseFloat("inf")));
  EXPECT_TRUE(std::isnan(*parseFloat("nan")));
  EXPECT_EQ(parseInteger("-12"), -12);
  EXPECT_EQ(parseInteger("+7"), 7);
  EXPECT_FALSE(parseInteger("1.0").has_value());
  EXPECT_FALSE(parseInteger("99999999999999999999").has_value());
}

TEST(Numbers, LinesEndAnywayAndContinue) {
  TextLines lines("\xEF\xBB\xBFv 1 \\\n  2 3\r\nf 1\r2\n\\\nlast\\");
  std::vector<std::pair<std::string, size_t>> got;
  while (const auto line = lines.next()) got.emplace_back(std::string(*line), lines.number());
  const std::vector<std::pair<std::string, size_t>> want{{"v 1    2 3", 1}, {"f 1", 3}, {"2", 4}, {" last", 5}};
  EXPECT_EQ(got, want);
  TextLines plain("a\\\nb", /*continuation=*/false);
  EXPECT_EQ(*plain.next(), "a\\");
  EXPECT_EQ(*plain.next(), "b");
}

}  // namespace
}  // namespace lancer
