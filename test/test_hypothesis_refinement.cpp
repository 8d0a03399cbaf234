// Refining a searching cloud's leading hypotheses (localizer/hypothesis_refinement.hpp): the best
// particle of each distinct region, best regions first; a pattern search that climbs onto a peak,
// stays within its reach and off forbidden poses; and, with every observation model, a particle
// standing beside the true pose climbs to it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "box_room_scan.hpp"
#include "localizer/filter/hypothesis_refinement.hpp"
#include "localizer/filter/particle_filter.hpp"
#include "localizer/models/observation_factory.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

cl::ObservationScore scored(double log_likelihood) {
  return {log_likelihood, 0.5};
}

// A peak at (x, y, yaw) = (1.0, 2.0, 0.3): ℓ = −(dx² + dy² + (r·dyaw)²) / s², r = 10 m, s = 1 cm.
std::optional<cl::ObservationScore> quadratic_peak(std::size_t, cl::Particle& candidate) {
  const cl::PoseState& s = candidate.state;
  const double d2 =
      std::pow(s.x - 1.0, 2) + std::pow(s.y - 2.0, 2) + std::pow(10.0 * (s.yaw - 0.3), 2);
  return scored(-d2 / 1e-4);
}

}  // namespace

TEST(LeadingHypotheses, TakesTheBestParticleOfEachRegionBestRegionFirst) {
  cl::ParticleSet particles{ct::particle_at(0.1, 0.1, 0.0), ct::particle_at(0.2, 0.2, 0.0),
                            ct::particle_at(5.1, 0.1, 0.0), ct::particle_at(9.1, 0.1, 0.0),
                            ct::particle_at(9.2, 0.2, 0.0)};
  // One pose with two velocities is one region.
  particles[4].velocity_x = 3.0;
  const std::vector<cl::ObservationScore> scores{scored(-5.0), scored(-1.0), scored(-9.0),
                                                 scored(-3.0), scored(-2.0)};
  const cl::KldBins bins;  // 0.5 m, 10°
  EXPECT_EQ(cl::leading_hypotheses(particles, scores, bins, 10),
            (std::vector<std::size_t>{1, 4, 2}));
  EXPECT_EQ(cl::leading_hypotheses(particles, scores, bins, 2), (std::vector<std::size_t>{1, 4}));
  EXPECT_TRUE(cl::leading_hypotheses(particles, scores, bins, 0).empty());
}

TEST(LeadingHypotheses, SkipsParticlesThatExplainNothing) {
  const cl::ParticleSet particles{ct::particle_at(0.1, 0.1, 0.0), ct::particle_at(5.1, 0.1, 0.0)};
  const std::vector<cl::ObservationScore> scores{scored(-std::numeric_limits<double>::infinity()),
                                                 scored(std::numeric_limits<double>::quiet_NaN())};
  EXPECT_TRUE(cl::leading_hypotheses(particles, scores, cl::KldBins{}, 5).empty());
}

TEST(RefineHypothesis, ClimbsOntoThePeakToWithinTheLastStep) {
  cl::Particle particle = ct::particle_at(1.17, 1.86, 0.31);
  cl::ObservationScore score = *quadratic_peak(0, particle);
  const double start = score.log_likelihood;
  cl::HypothesisRefinementConfig config;
  config.min_step_m = 0.005;
  config.max_evaluations = 200;
  cl::refine_hypothesis(particle, score, 0, {.step_m = 0.2, .range_m = 10.0}, config,
                        quadratic_peak);
  EXPECT_NEAR(particle.state.x, 1.0, 0.005);
  EXPECT_NEAR(particle.state.y, 2.0, 0.005);
  EXPECT_NEAR(particle.state.yaw, 0.3, 0.0005);
  EXPECT_GT(score.log_likelihood, start);
  EXPECT_EQ(score.log_likelihood, quadratic_peak(0, particle)->log_likelihood);
}

TEST(RefineHypothesis, StaysWithinTwiceItsFirstStep) {
  // The peak is 1 m away; with a first step of 0.1 m the particle may climb 0.2 m towards it.
  cl::Particle particle = ct::particle_at(2.0, 2.0, 0.3);
  cl::ObservationScore score = *quadratic_peak(0, particle);
  cl::HypothesisRefinementConfig config;
  config.max_evaluations = 500;
  cl::refine_hypothesis(particle, score, 0, {.step_m = 0.1, .range_m = 10.0}, config,
                        quadratic_peak);
  EXPECT_LE(std::hypot(particle.state.x - 2.0, particle.state.y - 2.0), 0.2 + 1e-12);
  EXPECT_LT(particle.state.x, 1.85);
}

TEST(RefineHypothesis, NeverTakesAForbiddenPoseAndSpendsAtMostItsBudget) {
  cl::Particle particle = ct::particle_at(1.3, 2.0, 0.3);
  cl::ObservationScore score = *quadratic_peak(0, particle);
  int calls = 0;
  // Everything west of x = 1.2 is off the floor.
  const auto fenced = [&](std::size_t index, cl::Particle& candidate) {
    ++calls;
    return candidate.state.x < 1.2 ? std::nullopt : quadratic_peak(index, candidate);
  };
  cl::HypothesisRefinementConfig config;
  config.max_evaluations = 25;
  cl::refine_hypothesis(particle, score, 0, {.step_m = 0.1, .range_m = 10.0}, config, fenced);
  EXPECT_GE(particle.state.x, 1.2);
  EXPECT_LE(calls, 25);
}

TEST(RefineHypothesis, ZeroStepLeavesTheParticle) {
  cl::Particle particle = ct::particle_at(1.3, 2.0, 0.3);
  cl::ObservationScore score = *quadratic_peak(0, particle);
  const cl::ObservationScore before = score;
  cl::refine_hypothesis(particle, score, 0, {.step_m = 0.0, .range_m = 10.0}, {}, quadratic_peak);
  EXPECT_EQ(particle.state.x, 1.3);
  EXPECT_EQ(score.log_likelihood, before.log_likelihood);
}

class RefinedModel : public ::testing::TestWithParam<std::string> {};

// A particle 0.2 m and 3° beside the pose a scan was taken from climbs the model's likelihood to
// within a few centimetres and a fraction of a degree of it.
TEST_P(RefinedModel, AParticleBesideTheTruthClimbsToIt) {
  const auto map = ct::make_box_room();
  const cl::Pose3 truth = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  const auto model = ct::model_with_scan(GetParam(), map, truth, 5);
  auto scratch = model->make_scratch();
  const auto evaluate = [&](std::size_t, cl::Particle& candidate) {
    return std::optional(model->score(candidate.state.to_pose(), scratch.get()));
  };

  cl::Particle particle = ct::particle_at(3.15, 2.37, 0.4 + 3.0 * M_PI / 180.0);
  cl::ObservationScore score = *evaluate(0, particle);
  cl::HypothesisRefinementConfig refinement;
  refinement.min_step_m = 0.005;
  refinement.max_evaluations = 300;
  cl::refine_hypothesis(particle, score, 0, {.step_m = 0.2, .range_m = 3.0}, refinement, evaluate);
  EXPECT_LT(std::hypot(particle.state.x - 3.0, particle.state.y - 2.5), 0.03);
  EXPECT_LT(std::abs(particle.state.yaw - 0.4), 0.5 * M_PI / 180.0);
  EXPECT_GE(score.log_likelihood, model->score(truth, scratch.get()).log_likelihood - 50.0);
}

INSTANTIATE_TEST_SUITE_P(AllModels, RefinedModel,
                         ::testing::ValuesIn(cl::observation_model_names()));

namespace {

struct BoxRoomFilter {
  conicloc::maps::PlaneMap map = ct::make_box_room();
  cl::FreeSpace free_space{map};
  cl::MotionModel motion{cl::MotionModelConfig{}, free_space};
  cl::ParticleFilter filter{cl::ParticleFilterConfig{}, motion, free_space};
};

}  // namespace

// Weighting a searching cloud moves its leading hypotheses up their peaks (the best score rises
// above what the same cloud scores unrefined) and nothing else; a converged cloud is not touched.
TEST(ParticleFilterRefinement, ClimbsOnlyTheLeadersOfASearchingCloud) {
  const cl::Pose3 truth = cl::make_pose(3.0, 2.5, 1.2, 0.4);
  BoxRoomFilter plain;
  BoxRoomFilter refined;
  std::mt19937_64 rng(3);
  ct::SyntheticScanOptions options;
  options.range_sigma_m = 0.01;
  const auto scan = ct::make_scan(plain.map, truth, options, rng);
  cl::ObservationConfig config;
  const auto model = cl::make_observation_model(config, plain.map, ct::vlp16());
  std::vector<std::unique_ptr<cl::ObservationModel::Scratch>> scratches;
  scratches.push_back(model->make_scratch());

  std::mt19937_64 rng_plain(7);
  std::mt19937_64 rng_refined(7);
  plain.filter.initialise_global(400, rng_plain);
  refined.filter.initialise_global(400, rng_refined);
  ASSERT_TRUE(refined.filter.searching());
  model->prepare(scan, plain.filter.position_bounds());
  const cl::ParticleSet before = refined.filter.particles();
  const auto plain_summary = plain.filter.weight(*model, scratches);
  const auto refined_summary =
      refined.filter.weight(*model, scratches, 0.0, {.step_m = 0.2, .range_m = 3.0});
  EXPECT_GT(refined_summary.best_log_likelihood, plain_summary.best_log_likelihood);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < before.size(); ++i) {
    const auto& a = before[i].state;
    const auto& b = refined.filter.particles()[i].state;
    if (a.x != b.x || a.y != b.y || a.yaw != b.yaw) ++moved;
  }
  EXPECT_GT(moved, 0u);
  EXPECT_LE(moved, cl::ParticleFilterConfig{}.refinement.hypotheses);

  BoxRoomFilter converged;
  cl::Vector6 sigma;
  sigma << 0.02, 0.02, 0.0, 0.0, 0.0, 0.005;
  converged.filter.initialise_at(cl::pose_state_from(truth), sigma, 200, rng);
  ASSERT_FALSE(converged.filter.searching());
  model->prepare(scan, converged.filter.position_bounds());
  const cl::ParticleSet tracked = converged.filter.particles();
  converged.filter.weight(*model, scratches, 0.0, {.step_m = 0.2, .range_m = 3.0});
  for (std::size_t i = 0; i < tracked.size(); ++i) {
    EXPECT_EQ(tracked[i].state.x, converged.filter.particles()[i].state.x);
    EXPECT_EQ(tracked[i].state.yaw, converged.filter.particles()[i].state.yaw);
  }
}
