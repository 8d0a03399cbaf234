// A scan's terms raised where the surfaces facing a direction hold few of its returns
// (direction_term_weights, correlated_terms.hpp): under one exponent a surface's share of the scan
// follows its returns, so along a hall the end walls count next to nothing; raised, each
// direction gets what the surfaces facing it are worth, while among the surfaces facing one
// direction the shares stay. The weighted beam sum equals its per-beam definition and stays within
// log 2 per beam of the mixture, and along a corridor the end walls count what they are worth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "localizer/conic/predicted_scan.hpp"
#include "localizer/models/beam_likelihood_sum.hpp"
#include "localizer/models/correlated_terms.hpp"
#include "localizer/models/observation_factory.hpp"
#include "model_test_name.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

constexpr double kRho = 0.36;  // (3 cm / 5 cm)², the defaults' correlation

double worth(double returns) {
  return returns / (1.0 + (returns - 1.0) * kRho);
}

// One polygon per surface, with these horizontal normals.
cl::Surfaces surfaces_facing(const std::vector<Eigen::Vector2d>& normals) {
  cl::Surfaces surfaces;
  for (std::size_t k = 0; k < normals.size(); ++k)
    surfaces.of_polygon.push_back(static_cast<int>(k));
  surfaces.count = normals.size();
  surfaces.horizontal_normal = normals;
  return surfaces;
}

}  // namespace

TEST(DirectionTermWeights, AHallsEndWallsCountWhatTheyAreWorth) {
  // Side walls (±x) of 400 returns each, end walls (±y) of 20 (as two terms of 12 and 8 returns,
  // a segment model's), a floor of 1000, and 60 returns on nothing.
  const cl::Surfaces surfaces = surfaces_facing({{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {0, 0}});
  cl::SurfaceTally tally(surfaces);
  std::vector<int> surface_of_term;
  double scan_returns = 0.0;
  const auto add = [&](int surface, double returns, int terms) {
    surface_of_term.insert(surface_of_term.end(), static_cast<std::size_t>(terms), surface);
    scan_returns += returns;
    if (surface >= 0) tally.add(surface, returns);
  };
  add(0, 400.0, 400);
  add(1, 400.0, 400);
  add(2, 20.0, 2);  // 10 + 10
  add(3, 20.0, 1);
  add(4, 1000.0, 1000);
  add(-1, 60.0, 60);
  const std::vector<double> weights =
      cl::direction_term_weights(surface_of_term, scan_returns, tally, kRho);
  ASSERT_EQ(weights.size(), surface_of_term.size());
  // One exponent τ = n_eff / returns gives y τ·40 returns; the end walls are worth 2·w(20) there.
  const double tau = (2.0 * worth(400.0) + 2.0 * worth(20.0) + worth(1000.0)) / 1900.0;
  const double end_raise = 2.0 * worth(20.0) / (tau * 40.0);
  EXPECT_GT(end_raise, 15.0);
  for (std::size_t i = 0; i < weights.size(); ++i) {
    const int s = surface_of_term[i];
    if (s == 2 || s == 3) {
      EXPECT_NEAR(weights[i], end_raise, 1e-9 * end_raise) << i;
    } else {
      // x gets τ·800 > 2·w(400): the side walls keep theirs; the floor and the unexplained too.
      EXPECT_EQ(weights[i], 1.0) << i;
    }
  }
}

TEST(DirectionTermWeights, SurfacesFacingOneDirectionKeepTheirShares) {
  // A wall of 400 returns and a door frame of 5 facing +x, a wall of 400 facing −y, a floor of 800:
  // x is short of its worth and both +x surfaces are raised alike — the frame is not made to
  // count as much as the wall beside it.
  const cl::Surfaces surfaces = surfaces_facing({{1, 0}, {1, 0}, {0, -1}, {0, 0}});
  cl::SurfaceTally tally(surfaces);
  tally.add(0, 400.0);
  tally.add(1, 5.0);
  tally.add(2, 400.0);
  tally.add(3, 800.0);
  const std::vector<int> surface_of_term = {0, 1, 2, 3};
  const auto weights = cl::direction_term_weights(surface_of_term, 1605.0, tally, kRho);
  const double tau = (2.0 * worth(400.0) + worth(5.0) + worth(800.0)) / 1605.0;
  EXPECT_NEAR(weights[0], (worth(400.0) + worth(5.0)) / (tau * 405.0), 1e-12);
  EXPECT_GT(weights[0], 1.0);
  EXPECT_EQ(weights[1], weights[0]);
  EXPECT_NEAR(weights[2], std::max(1.0, worth(400.0) / (tau * 400.0)), 1e-12);
  EXPECT_EQ(weights[3], 1.0);
}

TEST(DirectionTermWeights, NothingExplainedLeavesEqualWeights) {
  const cl::Surfaces surfaces = surfaces_facing({{1, 0}});
  const cl::SurfaceTally tally(surfaces);
  const std::vector<int> surface_of_term = {-1, -1, -1};
  EXPECT_EQ(cl::direction_term_weights(surface_of_term, 3.0, tally, kRho),
            std::vector<double>(3, 1.0));
}

TEST(BeamLikelihoodSum, WeightedMaxSumIsTheWeightedSumOfPerBeamMaxTerms) {
  // Inliers to far outliers, short and long, no prediction (+∞), a NaN prediction, an odd count
  // (the last beam outside the two-lane packets).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> range(0.5, 60.0), weight(0.05, 40.0);
  std::normal_distribution<double> residual(0.0, 0.3);
  const cl::BeamMixtureConfig config;
  const cl::RangeNoise noise;
  const cl::BeamMixture mixture(config, noise, conicloc::sensor::kMaxRange_m);
  std::vector<double> measured, predicted, weights, log_short_floors;
  for (int i = 0; i < 1001; ++i) {
    measured.push_back(range(rng));
    const int kind = i % 40;
    predicted.push_back(kind == 0   ? cl::PredictedRing::kNoReturn
                        : kind == 1 ? std::numeric_limits<double>::quiet_NaN()
                        : kind == 2 ? measured.back() - 20.0
                                    : measured.back() + residual(rng));
    weights.push_back(weight(rng));
    log_short_floors.push_back(mixture.floor(measured.back()).with_short);
  }
  const cl::BeamLikelihoodSum summer(config, noise, conicloc::sensor::kMaxRange_m);
  std::size_t inliers = 0;
  const double sum =
      summer.weighted_max_sum(measured, predicted, weights, log_short_floors, inliers);
  double expected = 0.0, expected_unit = 0.0;
  std::size_t expected_inliers = 0;
  const double log_hit = std::log(config.hit_weight / (std::sqrt(2.0 * M_PI) * noise.sigma_m));
  for (std::size_t i = 0; i < measured.size(); ++i) {
    const double r = measured[i] - predicted[i];
    const cl::BeamFloor floor = mixture.floor(measured[i]);
    double term = r < 0.0 ? floor.with_short : floor.without_short;  // NaN: the long floor
    const double hit = log_hit - r * r / (2.0 * noise.sigma_m * noise.sigma_m);
    if (hit > term) term = hit;
    expected += weights[i] * term;
    expected_unit += term;
    expected_inliers += std::abs(r) <= noise.inlier_gate_m() ? 1 : 0;
  }
  ASSERT_TRUE(std::isfinite(sum));
  EXPECT_NEAR(sum, expected, 1e-12 * std::abs(expected));
  EXPECT_EQ(inliers, expected_inliers);
  // max_sum() is the form with unit weights; it lies within log 2 per beam below the mixture's sum
  // (max(a, b) ≤ a + b ≤ 2 max(a, b)), and counts the same inliers.
  const std::vector<double> ones(measured.size(), 1.0);
  std::size_t max_inliers = 0, mixture_inliers = 0, unit_inliers = 0;
  const double max_form = summer.max_sum(measured, predicted, log_short_floors, max_inliers);
  EXPECT_NEAR(max_form, expected_unit, 1e-12 * std::abs(expected_unit));
  EXPECT_EQ(max_form,
            summer.weighted_max_sum(measured, predicted, ones, log_short_floors, unit_inliers));
  EXPECT_EQ(unit_inliers, max_inliers);
  std::vector<double> short_densities;
  for (const double z : measured) short_densities.push_back(mixture.short_density(z));
  const double mixture_sum = summer.sum(measured, predicted, short_densities, mixture_inliers);
  EXPECT_LE(max_form, mixture_sum + 1e-9);
  EXPECT_GE(max_form, mixture_sum - static_cast<double>(measured.size()) * std::log(2.0) - 1e-9);
  EXPECT_LT(max_form, mixture_sum - 1.0);  // and below it where the floor and the hit meet
  EXPECT_EQ(max_inliers, mixture_inliers);
}

// A corridor 30 m long, the sensor 8 m from one end: its side walls, floor and ceiling say
// nothing of the position along it; the end walls, 8 m and 22 m away and seen by a few per cent
// of the returns, say all of it. Under one exponent they count that few per cent of the scan's
// worth; raised to what they are worth along the corridor, a step of 10 cm along it costs several
// times as much (tempered as the filter tempers: τ = n_eff / terms).
class SurfaceWeightsAlongACorridor : public ::testing::TestWithParam<std::string> {};

TEST_P(SurfaceWeightsAlongACorridor, TheEndWallsCountWhatTheyAreWorth) {
  const auto map = ct::make_empty_room("corridor", {30.0, 2.4, 3.0});
  const cl::Pose3 truth = cl::make_pose(8.0, 1.1, 1.2, 0.3);
  std::mt19937_64 rng(2);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * M_PI / 180.0;
  options.range_sigma_m = 0.02;
  const auto scan = ct::make_scan(map, truth, options, rng);
  cl::ObservationConfig config;
  config.model = GetParam();
  const auto model = cl::make_observation_model(config, map, ct::vlp16());
  const auto scratch = model->make_scratch();
  const Eigen::AlignedBox3d box(truth.translation() - Eigen::Vector3d(0.5, 0.5, 0.1),
                                truth.translation() + Eigen::Vector3d(0.5, 0.5, 0.1));
  const cl::Pose3 along = cl::make_pose(8.1, 1.1, 1.2, 0.3);
  const cl::Pose3 across = cl::make_pose(8.0, 1.2, 1.2, 0.3);
  // The tempered log-likelihood lost by a step, with equal weights and weighed at the truth.
  struct Cost {
    double along = 0.0, across = 0.0;
  };
  const auto cost = [&](bool weighed) {
    model->prepare(scan, box);
    if (weighed) model->weigh_terms(truth, scratch.get());
    const double tempering =
        model->effective_terms(truth, scratch.get()) / static_cast<double>(model->term_count());
    const double at_truth = model->score(truth, scratch.get()).log_likelihood;
    return Cost{tempering * (at_truth - model->score(along, scratch.get()).log_likelihood),
                tempering * (at_truth - model->score(across, scratch.get()).log_likelihood)};
  };
  const Cost equal = cost(false), weighed = cost(true);
  // A new prepare() drops the weights.
  EXPECT_EQ(cost(false).along, equal.along);
  EXPECT_GT(equal.along, 0.0);
  EXPECT_GT(weighed.along, 3.0 * equal.along);
  // Across the corridor the side walls still pin the pose harder (a beam grazing a side wall
  // moves by the step over the sine of its angle to the wall).
  EXPECT_GT(weighed.across, weighed.along);
}

INSTANTIATE_TEST_SUITE_P(ConicModels, SurfaceWeightsAlongACorridor,
                         ::testing::Values("conic-beam", "conic-segment"),
                         conicloc::test::model_test_name);
