// The rings a searching cloud scores (localizer/filter/search_rings.hpp).
#include <gtest/gtest.h>

#include <vector>

#include "localizer/filter/search_rings.hpp"

namespace cl = conicloc::localizer;

TEST(SearchRings, SpreadOverTheElevationsOneFromTheMiddleOfEachBand) {
  EXPECT_EQ(cl::spread_rings(16, 4), (std::vector<int>{2, 6, 10, 14}));
  EXPECT_EQ(cl::spread_rings(16, 2), (std::vector<int>{4, 12}));
  EXPECT_EQ(cl::spread_rings(16, 1), (std::vector<int>{8}));
  EXPECT_EQ(cl::spread_rings(32, 4), (std::vector<int>{4, 12, 20, 28}));
  EXPECT_EQ(cl::spread_rings(16, 5), (std::vector<int>{1, 4, 8, 11, 14}));
  const std::vector<int> all = {0, 1, 2, 3};
  EXPECT_EQ(cl::spread_rings(4, 0), all);  // 0: every ring
  EXPECT_EQ(cl::spread_rings(4, 4), all);
  EXPECT_EQ(cl::spread_rings(4, 9), all);
  EXPECT_TRUE(cl::spread_rings(0, 4).empty());
}

TEST(SearchRings, KeepRingsEmptiesTheOthersAndKeepsTheirLasers) {
  conicloc::sensor::Scan scan;
  scan.index = 7;
  scan.start_time_s = 1.0;
  scan.end_time_s = 1.1;
  scan.partial = true;
  for (int k = 0; k < 4; ++k) {
    conicloc::sensor::RingScan ring;
    ring.ring = k;
    ring.channel = 3 - k;
    ring.elevation_rad = 0.1 * k;
    ring.vertical_offset_m = 0.01 * k;
    for (int i = 0; i <= k; ++i) ring.returns.push_back({.azimuth_rad = 0.5 * i, .range_m = 2.0});
    scan.rings.push_back(ring);
  }
  const std::vector<int> kept = {1, 3};
  const conicloc::sensor::Scan out = cl::keep_rings(scan, kept);
  EXPECT_EQ(out.index, 7U);
  EXPECT_EQ(out.start_time_s, 1.0);
  EXPECT_EQ(out.end_time_s, 1.1);
  EXPECT_TRUE(out.partial);
  ASSERT_EQ(out.rings.size(), 4U);
  for (int k = 0; k < 4; ++k) {
    const auto& ring = out.rings[static_cast<std::size_t>(k)];
    EXPECT_EQ(ring.ring, k);
    EXPECT_EQ(ring.channel, 3 - k);
    EXPECT_EQ(ring.elevation_rad, 0.1 * k);
    EXPECT_EQ(ring.vertical_offset_m, 0.01 * k);
    EXPECT_EQ(ring.returns.size(), k % 2 == 1 ? static_cast<std::size_t>(k + 1) : 0U);
  }
  EXPECT_EQ(out.valid_returns(), 6U);
}
