#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <vector>

#include "calib/level_scans.hpp"

namespace conicloc::calib {
namespace {

constexpr double kInterval_s = 0.1;  // 600 rpm
constexpr double kMaxClimb_mps = 0.02;

std::vector<double> scan_times(std::size_t n) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = 100.0 + kInterval_s * static_cast<double>(i);
  return t;
}

TEST(LevelScans, OnALevelFloorTheScansAreSpreadEvenlyAfterTheFirst) {
  const std::vector<double> t = scan_times(21);
  const std::vector<double> floor(21, 0.0);
  const LevelScanChoice choice = choose_level_scans(t, floor, 1, 4, kMaxClimb_mps);
  EXPECT_EQ(choice.climbing, 0U);
  EXPECT_EQ(choice.chosen, (std::vector<std::size_t>{1, 6, 11, 16}));
  EXPECT_TRUE(choose_level_scans(t, floor, 1, 0, kMaxClimb_mps).chosen.empty());
}

TEST(LevelScans, ScansBeforeTheFirstAreNeitherChosenNorCounted) {
  // A step up between scans 1 and 2 (a threshold): scans 1 and 2 climb, but before the first.
  const std::vector<double> t = scan_times(8);
  std::vector<double> floor(8, 0.08);
  floor[0] = floor[1] = 0.0;
  const LevelScanChoice choice = choose_level_scans(t, floor, 3, 100, kMaxClimb_mps);
  EXPECT_EQ(choice.climbing, 0U);
  EXPECT_EQ(choice.chosen, (std::vector<std::size_t>{3, 4, 5, 6, 7}));
  // From scan 2 on, scan 2 is counted (it rose from scan 1) and left out.
  const LevelScanChoice from_two = choose_level_scans(t, floor, 2, 100, kMaxClimb_mps);
  EXPECT_EQ(from_two.climbing, 1U);
  EXPECT_EQ(from_two.chosen, (std::vector<std::size_t>{3, 4, 5, 6, 7}));
}

TEST(LevelScans, ScansOnAStairAndAtItsEndsAreLeftOut) {
  // The floor at 0 for scans 0..9, up a stair at 0.65 m/s through scans 10..14 (each 6.5 cm
  // above the one before), level again at 0.325 m from scan 14 on.
  const std::vector<double> t = scan_times(20);
  std::vector<double> floor(20, 0.0);
  for (std::size_t i = 10; i < 20; ++i)
    floor[i] = 0.065 * static_cast<double>(std::min<std::size_t>(i, 14) - 9);
  const LevelScanChoice choice = choose_level_scans(t, floor, 1, 100, kMaxClimb_mps);
  // Scan 9 rises to 10 after it, 10..14 rise from the one before: 6 scans climb.
  EXPECT_EQ(choice.climbing, 6U);
  EXPECT_EQ(choice.chosen, (std::vector<std::size_t>{1, 2, 3, 4, 5, 6, 7, 8, 15, 16, 17, 18, 19}));
}

TEST(LevelScans, ARiseWithinTheRateIsLevelAndOneBeyondItIsNot) {
  // Times and heights exact in binary: a rise of exactly the rate times the interval is level.
  const std::vector<double> exact_t = {0.0, 0.5, 1.0};
  EXPECT_EQ(choose_level_scans(exact_t, std::vector<double>{0.0, 0.25, 0.5}, 1, 5, 0.5).climbing,
            0U);
  const std::vector<double> t = scan_times(3);
  const double within = 0.99 * kMaxClimb_mps * kInterval_s;
  const double beyond = 1.01 * kMaxClimb_mps * kInterval_s;
  EXPECT_EQ(choose_level_scans(t, std::vector<double>{0.8, 0.8 + within, 0.8 + 2 * within}, 1, 5,
                               kMaxClimb_mps)
                .chosen,
            (std::vector<std::size_t>{1, 2}));
  const LevelScanChoice falling = choose_level_scans(
      t, std::vector<double>{0.8, 0.8 - beyond, 0.8 - beyond}, 1, 5, kMaxClimb_mps);
  EXPECT_EQ(falling.chosen, (std::vector<std::size_t>{2}));
  EXPECT_EQ(falling.climbing, 1U);
}

TEST(LevelScans, AnUnknownFloorIsNotLevel) {
  const std::vector<double> t = scan_times(4);
  const LevelScanChoice choice = choose_level_scans(
      t, std::vector<double>{0.8, 0.8, std::numeric_limits<double>::quiet_NaN(), 0.8}, 1, 5,
      kMaxClimb_mps);
  EXPECT_EQ(choice.chosen, (std::vector<std::size_t>{}));
  EXPECT_EQ(choice.climbing, 3U);
}

TEST(LevelScans, RefusesFloorsThatDoNotMatchTheTimesAndAFirstScanWithNoneBefore) {
  const std::vector<double> t = scan_times(3);
  EXPECT_THROW(choose_level_scans(t, std::vector<double>(2, 0.8), 1, 5, kMaxClimb_mps),
               std::invalid_argument);
  EXPECT_THROW(choose_level_scans(t, std::vector<double>(3, 0.8), 0, 5, kMaxClimb_mps),
               std::invalid_argument);
}

}  // namespace
}  // namespace conicloc::calib
