// calib/unmapped_objects: a run of returns standing off its surface together is left out, a
// surface's own noise is not, and only neighbours on the same polygon judge a return.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "calib/unmapped_objects.hpp"

namespace conicloc::calib {
namespace {

// One scan line of `count` returns (laser 0, scan 0), 0.2° apart, in a shuffled order.
std::vector<Return> one_line(int count) {
  std::vector<Return> returns(count);
  for (int i = 0; i < count; ++i) returns[i].azimuth_rad = 0.2 * M_PI / 180.0 * ((i * 37) % count);
  return returns;
}

TEST(UnmappedObjects, ScanLinesGroupByLaserAndScanInAzimuthOrder) {
  std::vector<Return> returns = {{1, 0, 0.3, 1, 0},
                                 {0, 0, 0.2, 1, 0},
                                 {1, 0, 0.1, 1, 0},
                                 {1, 2, 0.5, 1, 0},
                                 {0, 0, 0.1, 1, 0}};
  const auto lines = scan_lines(returns);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], (std::vector<std::size_t>{4, 1}));  // scan 0, laser 0
  EXPECT_EQ(lines[1], (std::vector<std::size_t>{2, 0}));  // scan 0, laser 1
  EXPECT_EQ(lines[2], (std::vector<std::size_t>{3}));     // scan 2, laser 1
}

TEST(UnmappedObjects, RobustSigmaIgnoresUnassociatedReturnsAndOutliers) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 0.03);
  std::vector<double> residual(20000);
  std::vector<int> plane(residual.size(), 0);
  for (std::size_t i = 0; i < residual.size(); ++i) {
    residual[i] = noise(rng);
    if (i % 10 == 0) residual[i] = 5.0;                  // far off: moves the MAD a little
    if (i % 10 == 1) residual[i] = 50.0, plane[i] = -1;  // not on a plane: not counted
  }
  // On planes, 8/9 Gaussian and 1/9 far off: the median |e| is the Gaussian's quantile
  // p = (1 + 0.5·9/8)/2 = 0.78125, so 1.4826·Φ⁻¹(p)·σ = 1.151σ (1.4826σ if the 50 counted).
  EXPECT_NEAR(robust_sigma(residual, plane), 0.03 * 1.151, 0.0015);
  EXPECT_EQ(robust_sigma({}, {}), 0.0);
}

TEST(UnmappedObjects, AnObjectBeforeItsWallIsLeftOutAndTheWallKept) {
  std::mt19937_64 rng(11);
  constexpr double kSigma = 0.03;
  std::normal_distribution<double> noise(0.0, kSigma);
  const std::vector<Return> returns = one_line(400);
  const auto lines = scan_lines(returns);
  std::vector<double> residual(returns.size());
  std::vector<int> plane(returns.size(), 0);
  // In azimuth order: the wall, a box 6 cm before it over returns 150–189 (2σ off), the wall.
  const auto& line = lines.front();
  for (std::size_t k = 0; k < line.size(); ++k)
    residual[line[k]] = noise(rng) + (k >= 150 && k < 190 ? -0.06 : 0.0);
  const std::size_t left_out = leave_out_unmapped_objects(lines, residual, plane, kSigma, {});
  int box_out = 0, wall_out = 0;
  for (std::size_t k = 0; k < line.size(); ++k) {
    if (plane[line[k]] >= 0) continue;
    (k >= 150 && k < 190 ? box_out : wall_out) += 1;
  }
  EXPECT_EQ(left_out, static_cast<std::size_t>(box_out + wall_out));
  // All but about two at either edge, whose window holds barely more of the box than of the wall
  // (its median then the highest of 8 box returns, ~1.4σ above their level), and a chance miss
  // (a box median within the limit 4·√(π/2)·σ/√15 = 1.3σ: P ≈ 1.4 % each).
  EXPECT_GE(box_out, 34);
  // Only right beside it, where the box holds 7 of a wall return's 15 and the median is the lowest
  // of the wall's 8 (about −1.4σ, past the 1.3σ bound).
  EXPECT_LE(wall_out, 2);
}

TEST(UnmappedObjects, ASurfacesOwnNoiseLosesAlmostNothing) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.03);
  const std::vector<Return> returns = one_line(20000);
  const auto lines = scan_lines(returns);
  std::vector<double> residual(returns.size());
  for (double& r : residual) r = noise(rng);
  std::vector<int> plane(returns.size(), 0);
  // κ = 4: about one return in 10⁴ by chance (neighbouring medians are correlated).
  EXPECT_LE(leave_out_unmapped_objects(lines, residual, plane, 0.03, {}), 10u);
  // Half the scale: a median now strays past 2σ_med, about one in 20.
  std::vector<int> tight(returns.size(), 0);
  EXPECT_GT(leave_out_unmapped_objects(lines, residual, tight, 0.015, {}), 400u);
}

TEST(UnmappedObjects, OnlyNeighboursOnTheSamePolygonJudge) {
  const std::vector<Return> returns = one_line(100);
  const auto lines = scan_lines(returns);
  const auto& line = lines.front();
  std::vector<double> residual(returns.size(), 0.0);
  std::vector<int> plane(returns.size(), 0);
  for (std::size_t k = 0; k < line.size(); ++k) {
    if (k >= 40 && k < 60) plane[line[k]] = 1, residual[line[k]] = -0.2;  // all off: left out
    if (k >= 70 && k < 74) plane[line[k]] = 2, residual[line[k]] = -0.2;  // a sliver: kept
    if (k >= 80 && k < 85) plane[line[k]] = -1, residual[line[k]] = 9.0;  // not on a plane
  }
  const std::vector<int> before = plane;
  leave_out_unmapped_objects(lines, residual, plane, 0.01, {});
  for (std::size_t k = 0; k < line.size(); ++k) {
    const std::size_t i = line[k];
    if (before[i] == 1)
      EXPECT_EQ(plane[i], -1) << k;
    else
      EXPECT_EQ(plane[i], before[i]) << k;  // polygon 0 beside them, the sliver, the unassociated
  }
}

}  // namespace
}  // namespace conicloc::calib
