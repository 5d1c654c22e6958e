#include <gtest/gtest.h>

#include <filesystem>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "scene/rays_file.h"

namespace lancer {
namespace {

std::string writeTemp(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

// The error message must name the file and the line.
void expectError(const std::string& text, const std::string& needle) {
  const std::string path = writeTemp("lancer_bad_rays.txt", text);
  try {
    readRaysFile(path);
    FAIL() << "expected an error for: " << text;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path), std::string::npos) << message;
    EXPECT_NE(message.find(needle), std::string::npos) << message;
  }
}

TEST(RaysFile, ReadsDecimalHexAndComments) {
  const std::string path = writeTemp("lancer_rays.txt",
                                     "# header\n"
                                     "0 0 0 0 0 1\n"
                                     "\n"
                                     "  1.5 -2 3e2   0x1p-1 0 -0.0  # trailing comment\n"
                                     "0x1.8p+0 0 0 1 1 1\n");
  const auto rays = readRaysFile(path);
  ASSERT_EQ(rays.size(), 3u);
  EXPECT_EQ(rays[1].origin, glm::vec3(1.5f, -2.0f, 300.0f));
  EXPECT_EQ(rays[1].dir.x, 0.5f);
  EXPECT_TRUE(std::signbit(rays[1].dir.z));
  EXPECT_EQ(rays[2].origin.x, 1.5f);
}

TEST(RaysFile, RoundTripsBitExactly) {
  std::vector<Ray> rays{{{0.1f, -0.0f, 1e-30f}, {3.0f, 1e-20f, -7.25f}}, {{1, 2, 3}, {0, 0, -1}}};
  const auto path = (std::filesystem::temp_directory_path() / "lancer_roundtrip.txt").string();
  writeRaysFile(path, rays, "test");
  const auto back = readRaysFile(path);
  ASSERT_EQ(back.size(), rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(std::memcmp(&back[i].origin, &rays[i].origin, sizeof(glm::vec3)), 0);
    EXPECT_EQ(std::memcmp(&back[i].dir, &rays[i].dir, sizeof(glm::vec3)), 0);
  }
}

TEST(RaysFile, BadLinesNameFileAndLine) {
  expectError("0 0 0 0 0 1\n0 0 0 0 1\n", ":2:");
  expectError("0 0 0 0 0 1 7\n", ":1:");
  expectError("0 0 zero 0 0 1\n", "'zero' is not a number");
  expectError("0 0 0 nan 0 1\n", "ray 0: NaN or infinite");
  expectError("0 0 0 0 0 1\n0 inf 0 0 0 1\n", "ray 1: NaN or infinite");
  expectError("1 2 3 0 0 0\n", "zero direction");
  expectError("1 2 3 0 -0.0 0\n", "zero direction");
  EXPECT_THROW(readRaysFile("/nonexistent/rays.txt"), InputError);
  // A NUL byte ended the parse of its line and the rest was dropped unread.
  expectError(std::string("0 0 0 0 0 1\0 9 9\n", 17), ":1: NUL byte");
}

TEST(RaysFile, StreamsAndMultiLineCommentsRoundTrip) {
  // Each line of a comment is commented out: none of it may read back as a ray.
  const std::vector<Ray> rays{{{1, 2, 3}, {0, 0, 1}}};
  std::stringstream text;
  writeRays(text, rays, "first line\n0 0 0 1 1 1");
  const auto back = readRays(text, "stream");
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].origin, rays[0].origin);
  // A NUL inside a comment is part of the comment.
  std::istringstream commented(std::string("1 2 3 0 0 1 # \0\n", 16));
  EXPECT_EQ(readRays(commented, "stream").size(), 1u);
}

}  // namespace
}  // namespace lancer
