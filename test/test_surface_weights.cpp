// A scan's terms weighed by what the surface each meets is worth (correlated_terms.hpp): a
// surface of n returns is worth n / (1 + (n − 1)ρ) independent terms however many returns it has,
// so the weights share the scan's worth among its surfaces by that, not by their returns. The
// weighted beam sum equals its per-beam definition, and along a corridor, whose walls say nothing
// of the position along it, the far end walls count what they are worth.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "localizer/conic/predicted_scan.hpp"
#include "localizer/models/beam_likelihood_sum.hpp"
#include "localizer/models/correlated_terms.hpp"
#include "localizer/models/observation_factory.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

// Two polygons on two surfaces: one per wall of the box room.
cl::Surfaces two_surfaces() {
  return {{0, 1}, 2};
}

}  // namespace

TEST(SurfaceTermWeights, EachSurfaceSharesTheScanByItsWorthNotByItsReturns) {
  const cl::Surfaces surfaces = two_surfaces();
  cl::SurfaceTally tally(surfaces);
  // A wall seen by 100 returns, a door frame by 4, and 10 returns on nothing.
  std::vector<int> surface_of_term;
  for (int i = 0; i < 100; ++i) surface_of_term.push_back(0);
  for (int i = 0; i < 4; ++i) surface_of_term.push_back(1);
  for (int i = 0; i < 10; ++i) surface_of_term.push_back(-1);
  tally.add(0, 100.0);
  tally.add(1, 4.0);
  const std::vector<double> sizes(surface_of_term.size(), 1.0);
  const double rho = 0.36;
  const std::vector<double> weights = cl::surface_term_weights(surface_of_term, sizes, tally, rho);
  ASSERT_EQ(weights.size(), surface_of_term.size());
  double total = 0.0, wall = 0.0, frame = 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    total += weights[i];
    if (surface_of_term[i] == 0) wall += weights[i];
    if (surface_of_term[i] == 1) frame += weights[i];
  }
  // The scan keeps its worth: Σ r = the terms.
  EXPECT_NEAR(total, 114.0, 1e-12);
  // The wall's and the frame's shares are in the ratio of their worths, 100/36.64 to 4/2.08,
  // where equal weights gave them 100 to 4.
  const double wall_worth = 100.0 / (1.0 + 99.0 * rho), frame_worth = 4.0 / (1.0 + 3.0 * rho);
  EXPECT_NEAR(wall / frame, wall_worth / frame_worth, 1e-12);
  // A term on no surface counts the scan's mean worth per term.
  const double mean_worth = (wall_worth + frame_worth) / 114.0;
  EXPECT_NEAR(weights.back() / weights.front(), mean_worth * (1.0 + 99.0 * rho), 1e-12);
}

TEST(SurfaceTermWeights, TermsOfSeveralReturnsCountByTheirReturns) {
  // conic-segment's terms: segments of 30 and 10 returns on one surface, 5 on another.
  const cl::Surfaces surfaces = two_surfaces();
  cl::SurfaceTally tally(surfaces);
  tally.add(0, 40.0);
  tally.add(1, 5.0);
  const std::vector<int> surface_of_term = {0, 0, 1};
  const std::vector<double> sizes = {30.0, 10.0, 5.0};
  const double rho = 0.36;
  const auto weights = cl::surface_term_weights(surface_of_term, sizes, tally, rho);
  EXPECT_EQ(weights[0], weights[1]);  // one surface, one weight per return
  EXPECT_NEAR(30.0 * weights[0] + 10.0 * weights[1] + 5.0 * weights[2], 45.0, 1e-12);
  EXPECT_NEAR(weights[2] / weights[0], (1.0 + 39.0 * rho) / (1.0 + 4.0 * rho), 1e-12);
}

TEST(SurfaceTermWeights, NothingExplainedLeavesEqualWeights) {
  const cl::Surfaces surfaces = two_surfaces();
  const cl::SurfaceTally tally(surfaces);
  const std::vector<int> surface_of_term = {-1, -1, -1};
  const std::vector<double> sizes = {1.0, 1.0, 1.0};
  EXPECT_EQ(cl::surface_term_weights(surface_of_term, sizes, tally, 0.36),
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
  double expected = 0.0;
  std::size_t expected_inliers = 0;
  const double log_hit = std::log(config.hit_weight / (std::sqrt(2.0 * M_PI) * noise.sigma_m));
  for (std::size_t i = 0; i < measured.size(); ++i) {
    const double r = measured[i] - predicted[i];
    const cl::BeamFloor floor = mixture.floor(measured[i]);
    double term = r < 0.0 ? floor.with_short : floor.without_short;  // NaN: the long floor
    const double hit = log_hit - r * r / (2.0 * noise.sigma_m * noise.sigma_m);
    if (hit > term) term = hit;
    expected += weights[i] * term;
    expected_inliers += std::abs(r) <= noise.inlier_gate_m() ? 1 : 0;
  }
  ASSERT_TRUE(std::isfinite(sum));
  EXPECT_NEAR(sum, expected, 1e-12 * std::abs(expected));
  EXPECT_EQ(inliers, expected_inliers);
}

// A corridor 30 m long, the sensor 8 m from one end: its side walls, floor and ceiling say
// nothing of the position along it; the end walls, 8 m and 22 m away and seen by a few per cent
// of the returns, say all of it. With equal weights they count that few per cent of the scan's
// worth; weighed by surface, each counts what one surface is worth, and a step of 10 cm along the
// corridor costs several times as much (tempered as the filter tempers: τ = n_eff / terms).
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
  EXPECT_GT(equal.along, 0.0);
  EXPECT_GT(weighed.along, 3.0 * equal.along);
  // Across the corridor the side walls still pin the pose harder (a beam grazing a side wall
  // moves by the step over the sine of its angle to the wall).
  EXPECT_GT(weighed.across, weighed.along);
}

INSTANTIATE_TEST_SUITE_P(ConicModels, SurfaceWeightsAlongACorridor,
                         ::testing::Values("conic-beam", "conic-segment"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param == "conic-beam" ? std::string("conic_beam")
                                                             : std::string("conic_segment");
                         });
