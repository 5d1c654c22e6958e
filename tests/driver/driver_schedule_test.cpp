// The dispatcher's schedules (driver/schedule.h): the sorted order is a
// permutation of the lattice rays by (key, index), the key's octant and Morton
// bits, the chip's sort estimate, and the one-line error of an unknown name.

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "driver/schedule.h"

namespace lancer {
namespace {

fx::QRay rayAt(std::array<int64_t, 3> org, std::array<int64_t, 3> dir) {
  fx::QRay r;
  r.org = org;
  r.dir = dir;
  return r;
}

TEST(Schedule, NamesRoundTripAndAnUnknownOneIsAnError) {
  for (const std::string& name : scheduleNames()) EXPECT_EQ(toString(parseSchedule(name)), name);
  try {
    parseSchedule("random");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "--schedule random: no such schedule (available: fifo, sorted, treelet)");
  }
}

TEST(Schedule, TheKeyIsTheOriginsMortonCodeOverTheOctant) {
  constexpr int kDrop = fx::kPosBits - kSortOriginBits;
  const std::array<int64_t, 3> plus{1, 1, 1};
  EXPECT_EQ(rayOrderKey(rayAt({0, 0, 0}, plus)), 0u);
  // x is the most significant of each triple of Morton bits, z the least; the
  // octant's three bits below them.
  EXPECT_EQ(rayOrderKey(rayAt({int64_t(1) << kDrop, 0, 0}, plus)), 4u << 3);
  EXPECT_EQ(rayOrderKey(rayAt({0, int64_t(1) << kDrop, 0}, plus)), 2u << 3);
  EXPECT_EQ(rayOrderKey(rayAt({0, 0, int64_t(1) << kDrop}, plus)), 1u << 3);
  EXPECT_EQ(rayOrderKey(rayAt({int64_t(2) << kDrop, 0, 0}, plus)), 32u << 3);
  // Bits below the key's cells do not count.
  EXPECT_EQ(rayOrderKey(rayAt({(int64_t(1) << kDrop) - 1, 0, 0}, plus)), 0u);
  // A negative component sets its octant bit.
  EXPECT_EQ(rayOrderKey(rayAt({0, 0, 0}, {-1, 1, 1})), 1u);
  EXPECT_EQ(rayOrderKey(rayAt({0, 0, 0}, {1, 1, -1})), 4u);
  // The origin before the direction: a ray from the next cell sorts after every octant of this one.
  EXPECT_GT(rayOrderKey(rayAt({0, 0, int64_t(1) << kDrop}, plus)), rayOrderKey(rayAt({0, 0, 0}, {-1, -1, -1})));
  // The far corner: every bit set, in kSortKeyBits.
  const int64_t top = fx::kPosMax;
  const uint64_t key = rayOrderKey(rayAt({top, top, top}, {-1, -1, -1}));
  EXPECT_EQ(key, (uint64_t(1) << kSortKeyBits) - 1);
}

TEST(Schedule, SortedIsAPermutationOfTheLatticeRaysInKeyOrder) {
  std::mt19937_64 rng(11);
  std::vector<std::optional<QuantizedRay>> rays(5000);
  for (size_t i = 0; i < rays.size(); ++i) {
    if (rng() % 7 == 0) continue;  // outside the lattice
    QuantizedRay q;
    q.q = rayAt({int64_t(rng() % fx::kPosMax), int64_t(rng() % fx::kPosMax), int64_t(rng() % 64)},
                {int64_t(rng() % 3) - 1, 1, int64_t(rng() % 3) - 1});
    rays[i] = q;
  }
  const std::vector<uint32_t> fifo = dispatchOrder(Schedule::Fifo, rays);
  const std::vector<uint32_t> sorted = dispatchOrder(Schedule::Sorted, rays);
  ASSERT_TRUE(std::is_sorted(fifo.begin(), fifo.end()));
  for (uint32_t i : fifo) EXPECT_TRUE(rays[i].has_value());
  EXPECT_EQ(size_t(std::count_if(rays.begin(), rays.end(), [](const auto& r) { return r.has_value(); })), fifo.size());
  std::vector<uint32_t> same = sorted;
  std::sort(same.begin(), same.end());
  EXPECT_EQ(same, fifo);
  for (size_t k = 1; k < sorted.size(); ++k) {
    const uint64_t a = rayOrderKey(rays[sorted[k - 1]]->q), b = rayOrderKey(rays[sorted[k]]->q);
    ASSERT_TRUE(a < b || (a == b && sorted[k - 1] < sorted[k])) << "at " << k;
  }
  EXPECT_NE(sorted, fifo);
  EXPECT_EQ(dispatchOrder(Schedule::Sorted, rays), sorted);  // a function of the rays
}

TEST(Schedule, TheChipsSortIsTheLargerOfItsLanesAndItsDramTime) {
  mem::MemoryConfig m;
  m.clockMhz = 100;
  m.dram.gbps = 12.8;  // 128 bytes a cycle
  const uint64_t rayBytes = uint64_t(fx::kIsectRayBits + 7) / 8;
  const SortCost c = chipSortCost(1000, m);
  EXPECT_EQ(c.rays, 1000u);
  EXPECT_EQ(c.sorts, 1u);
  EXPECT_EQ(c.dramBytes, 1000 * (kSortRecordBytes * (1 + 2 * kSortPasses) + 2 * rayBytes));
  const uint64_t dramCycles = (c.dramBytes + 127) / 128;
  const uint64_t laneCycles = (1000 * uint64_t(kSortPasses) + kSortLanes - 1) / kSortLanes;
  EXPECT_EQ(c.chipCycles, std::max(dramCycles, laneCycles));
  m.dram.gbps = 1e4;  // DRAM no object: the lanes set the time
  EXPECT_EQ(chipSortCost(1000, m).chipCycles, laneCycles);
  SortCost sum = c;
  sum += c;
  EXPECT_EQ(sum.rays, 2000u);
  EXPECT_EQ(sum.sorts, 2u);
  EXPECT_EQ(nlohmann::json(c)["chip_cycles_estimate"], c.chipCycles);
}

}  // namespace
}  // namespace lancer
