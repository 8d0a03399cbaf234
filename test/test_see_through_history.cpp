// The lost test's memory: the share of returns seen through walls, in three scans of four over
// seconds, tells a look-alike that sees through a few per cent of its walls in every scan from a
// correct pose passing a door.
#include <gtest/gtest.h>

#include "localizer/filter/see_through_history.hpp"

namespace cl = conicloc::localizer;

namespace {

// Scans every 0.1 s from time 0, the k-th with fraction(k); a 2 s window, its lower quartile
// against 1.5 %, a pose checked after 1 s.
template <typename Fraction>
cl::SeeThroughHistory feed(int scans, Fraction fraction) {
  cl::SeeThroughHistory history(
      {.window_s = 2.0, .quantile = 0.25, .max_fraction = 0.015, .check_s = 1.0, .max_gap_s = 1.0});
  for (int k = 0; k < scans; ++k) history.add(0.1 * k, fraction(k));
  return history;
}

}  // namespace

TEST(SeeThroughHistory, JudgesOnlyOnceTheWindowIsCovered) {
  // 3 % in every scan (a mirrored look-alike): 2.0 s are covered by the 21st scan (0.0 … 2.0 s).
  const auto constant = [](int) { return 0.03; };
  const auto short_history = feed(20, constant);
  EXPECT_FALSE(short_history.covered());
  EXPECT_FALSE(short_history.sees_through());
  EXPECT_FALSE(short_history.clean());
  const auto full = feed(21, constant);
  EXPECT_TRUE(full.covered());
  EXPECT_TRUE(full.sees_through());
  EXPECT_FALSE(full.clean());
  EXPECT_DOUBLE_EQ(full.tested_quantile(), 0.03);
}

TEST(SeeThroughHistory, AClearPoseIsCheckedBeforeTheWindowIsCovered) {
  const auto clear = [](int) { return 0.0; };
  EXPECT_FALSE(feed(10, clear).clean());  // 0.9 s
  const auto second = feed(11, clear);    // 1.0 s
  EXPECT_TRUE(second.clean());
  EXPECT_FALSE(second.covered());
  // A look-alike fails the check from its first second on.
  const auto look_alike = feed(11, [](int) { return 0.022; });
  EXPECT_FALSE(look_alike.clean());
  EXPECT_FALSE(look_alike.sees_through());  // the alarm waits for the whole window
}

TEST(SeeThroughHistory, ABurstAtACorrectPoseStaysClean) {
  // A door passage: 11 of 21 scans at 2.5–9.5 %, the others clear. Their mean (3 %) is what a
  // look-alike gives; their lower quartile is 0.
  const auto burst = feed(21, [](int k) { return k >= 10 ? 0.025 + 0.007 * (k - 10) : 0.0; });
  EXPECT_TRUE(burst.clean());
  EXPECT_FALSE(burst.sees_through());
  EXPECT_DOUBLE_EQ(burst.tested_quantile(), 0.0);
  // Held for 16 of the 21 scans, the same readings are no burst: the 6th smallest is 2.5 %.
  const auto held = feed(21, [](int k) { return k >= 5 ? 0.025 + 0.007 * (k - 5) : 0.0; });
  EXPECT_TRUE(held.sees_through());
  EXPECT_FALSE(held.clean());
  EXPECT_DOUBLE_EQ(held.tested_quantile(), 0.025);
}

TEST(SeeThroughHistory, OldScansLeaveTheWindow) {
  // 10 % for the first 2 s, then 3 s clean: only the last 2 s (and the scan just before them)
  // count.
  const auto history = feed(51, [](int k) { return k < 20 ? 0.10 : 0.0; });
  EXPECT_TRUE(history.clean());
  EXPECT_DOUBLE_EQ(history.tested_quantile(), 0.0);
  // While the old scans fill most of the window, three scans in four still see through.
  const auto early = feed(25, [](int k) { return k < 20 ? 0.10 : 0.0; });
  EXPECT_TRUE(early.sees_through());
}

TEST(SeeThroughHistory, AGapInTheCaptureStartsAfresh) {
  // Two scans at 5 % with 3 s of nothing between them would span the 2 s window.
  cl::SeeThroughHistory history(
      {.window_s = 2.0, .quantile = 0.25, .max_fraction = 0.015, .check_s = 1.0, .max_gap_s = 1.0});
  history.add(0.0, 0.05);
  history.add(3.0, 0.05);
  EXPECT_FALSE(history.covered());
  EXPECT_FALSE(history.sees_through());
  // Time running back starts afresh too.
  for (int k = 0; k <= 20; ++k) history.add(3.0 + 0.1 * k, 0.05);
  ASSERT_TRUE(history.sees_through());
  history.add(1.0, 0.05);
  EXPECT_FALSE(history.covered());
}

TEST(SeeThroughHistory, ClearForgetsEveryScan) {
  auto history = feed(30, [](int) { return 0.05; });
  ASSERT_TRUE(history.sees_through());
  history.clear();
  EXPECT_FALSE(history.covered());
  EXPECT_FALSE(history.sees_through());
  EXPECT_DOUBLE_EQ(history.tested_quantile(), 0.0);
}

TEST(SeeThroughHistory, APoseNotYetCheckedIsJudgedOverTheShorterWindow) {
  // The defaults: 5 s for a checked pose, 2.5 s for one a restart converged on and never clean.
  cl::SeeThroughHistory look_alike({});
  for (int k = 0; k <= 25; ++k) look_alike.add(0.1 * k, 0.03);  // 3 % in every scan for 2.5 s
  EXPECT_TRUE(look_alike.sees_through(false));
  EXPECT_FALSE(look_alike.sees_through(true));  // the 5 s window is not covered yet
  // A passage at a correct pose: 5 % for 1.7 s among clear scans is not judged a look-alike.
  cl::SeeThroughHistory passage({});
  for (int k = 0; k <= 25; ++k) passage.add(0.1 * k, k >= 4 && k < 21 ? 0.05 : 0.0);
  EXPECT_FALSE(passage.sees_through(false));
}
