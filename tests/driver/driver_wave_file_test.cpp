// A run of many jobs keeps every job's waveform (driver/wave_file.h).

#include <gtest/gtest.h>

#include "driver/wave_file.h"

namespace lancer {
namespace {

TEST(WaveFile, EachJobAfterTheFirstGetsANumberedFile) {
  EXPECT_EQ(nextWaveFile("/tmp/lancer-wave-test/a.fst"), "/tmp/lancer-wave-test/a.fst");
  EXPECT_EQ(nextWaveFile("/tmp/lancer-wave-test/a.fst"), "/tmp/lancer-wave-test/a.1.fst");
  EXPECT_EQ(nextWaveFile("/tmp/lancer-wave-test/a.fst"), "/tmp/lancer-wave-test/a.2.fst");
  EXPECT_EQ(nextWaveFile("/tmp/lancer-wave-test/b.fst"), "/tmp/lancer-wave-test/b.fst");
  EXPECT_EQ(nextWaveFile(""), "");  // off stays off
}

}  // namespace
}  // namespace lancer
