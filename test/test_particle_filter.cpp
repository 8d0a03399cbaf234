// Mechanics of the particle filter: log-domain weights, resampling, KLD bounds, initialisation,
// motion, de-skew, determinism.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numeric>
#include <set>

#include "localizer/filter/deskew.hpp"
#include "localizer/filter/free_space.hpp"
#include "localizer/filter/log_weights.hpp"
#include "localizer/filter/motion_model.hpp"
#include "localizer/filter/particle_filter.hpp"
#include "localizer/filter/pose_estimate.hpp"
#include "localizer/filter/relative_motion.hpp"
#include "localizer/filter/resampling.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

TEST(LogWeights, LogSumExpMatchesDirectSumAndSurvivesHugeMagnitudes) {
  const std::vector<double> small{std::log(0.2), std::log(0.3), std::log(0.5)};
  EXPECT_NEAR(cl::log_sum_exp(small), 0.0, 1e-12);
  // exp(−10000) underflows; the shifted sum does not.
  const std::vector<double> huge{-10000.0, -10000.0 + std::log(3.0)};
  EXPECT_NEAR(cl::log_sum_exp(huge), -10000.0 + std::log(4.0), 1e-9);
}

TEST(LogWeights, MinusInfinityTermsAreIgnoredAndAllMinusInfinityIsMinusInfinity) {
  const std::vector<double> some{-kInf, std::log(2.0), -kInf};
  EXPECT_NEAR(cl::log_sum_exp(some), std::log(2.0), 1e-12);
  const std::vector<double> none{-kInf, -kInf};
  EXPECT_EQ(cl::log_sum_exp(none), -kInf);
  EXPECT_EQ(cl::log_sum_exp(std::vector<double>{}), -kInf);
  const std::vector<double> with_nan{std::nan(""), 0.0};
  EXPECT_NEAR(cl::log_sum_exp(with_nan), 0.0, 1e-12);
}

TEST(LogWeights, NormaliseAllMinusInfinityGivesUniformAndReportsIt) {
  std::vector<double> w{-kInf, -kInf, std::nan(""), -kInf};
  EXPECT_EQ(cl::normalise_log_weights(w), -kInf);
  for (const double v : w) EXPECT_NEAR(v, -std::log(4.0), 1e-12);
  EXPECT_NEAR(cl::effective_sample_size(w), 4.0, 1e-9);
}

TEST(LogWeights, NormaliseSumsToOne) {
  std::vector<double> w{-5000.0, -5001.0, -kInf, -5003.0};
  const double normaliser = cl::normalise_log_weights(w);
  EXPECT_NEAR(normaliser, cl::log_sum_exp(std::vector<double>{-5000.0, -5001.0, -5003.0}), 1e-9);
  EXPECT_NEAR(cl::log_sum_exp(w), 0.0, 1e-12);
  EXPECT_EQ(w[2], -kInf);
}

TEST(LogWeights, EffectiveSampleSizeBounds) {
  const std::vector<double> uniform(10, -std::log(10.0));
  EXPECT_NEAR(cl::effective_sample_size(uniform), 10.0, 1e-9);
  std::vector<double> one_hot(10, -kInf);
  one_hot[3] = 0.0;
  EXPECT_NEAR(cl::effective_sample_size(one_hot), 1.0, 1e-12);
  const std::vector<double> two{std::log(0.5), std::log(0.5), -kInf};
  EXPECT_NEAR(cl::effective_sample_size(two), 2.0, 1e-12);
}

TEST(Resampling, LowVarianceCopiesAreFloorOrCeilOfExpectedCount) {
  const std::vector<double> weights{0.1, 0.35, 0.05, 0.5};
  std::vector<double> log_w;
  for (const double w : weights) log_w.push_back(std::log(w));
  const std::size_t n = 40;
  // Offsets off the exact ties (pointer == cumulative weight), where rounding decides.
  for (const double u0 : {0.01, 0.13, 0.5, 0.999}) {
    const auto selected = cl::low_variance_resample(log_w, n, u0);
    ASSERT_EQ(selected.size(), n);
    EXPECT_TRUE(std::is_sorted(selected.begin(), selected.end()));
    for (std::size_t i = 0; i < weights.size(); ++i) {
      const auto copies = std::count(selected.begin(), selected.end(), i);
      EXPECT_GE(copies, std::floor(n * weights[i])) << "u0 " << u0 << " index " << i;
      EXPECT_LE(copies, std::ceil(n * weights[i])) << "u0 " << u0 << " index " << i;
    }
  }
}

TEST(Resampling, LowVarianceIsUnbiasedOverTheOffset) {
  // E[copies_i] = n·w_i when u0 ~ U[0, 1): average over a fine grid of offsets.
  const std::vector<double> weights{0.013, 0.287, 0.0, 0.4, 0.3};
  std::vector<double> log_w;
  for (const double w : weights) log_w.push_back(std::log(w));
  const std::size_t n = 7;
  std::vector<double> mean_copies(weights.size(), 0.0);
  const int offsets = 10000;
  for (int k = 0; k < offsets; ++k) {
    for (const std::size_t i : cl::low_variance_resample(log_w, n, (k + 0.5) / offsets)) {
      mean_copies[i] += 1.0 / offsets;
    }
  }
  for (std::size_t i = 0; i < weights.size(); ++i) {
    EXPECT_NEAR(mean_copies[i], n * weights[i], 1e-3) << "index " << i;
  }
}

TEST(Resampling, ZeroWeightParticlesAreNeverSelected) {
  const std::vector<double> log_w{-kInf, -kInf, 0.0, -kInf};
  for (const std::size_t i : cl::low_variance_resample(log_w, 5, 0.0)) EXPECT_EQ(i, 2u);
}

TEST(Resampling, KldSampleCountFollowsFox2003) {
  EXPECT_EQ(cl::kld_sample_count(0, 0.05, 2.326), 1u);
  EXPECT_EQ(cl::kld_sample_count(1, 0.05, 2.326), 1u);
  // k = 2: (1/0.1)·(1 − 2/9 + sqrt(2/9)·2.326)³ = 10·(1.8745...)³ ≈ 65.87 → 66.
  const double a = 2.0 / 9.0;
  const double expected = std::ceil(10.0 * std::pow(1.0 - a + std::sqrt(a) * 2.326, 3.0));
  EXPECT_EQ(cl::kld_sample_count(2, 0.05, 2.326), static_cast<std::size_t>(expected));
  // Grows with the number of bins, shrinks with a looser bound.
  std::size_t previous = 0;
  for (std::size_t k = 2; k < 2000; k *= 2) {
    const std::size_t n = cl::kld_sample_count(k, 0.05, 2.326);
    EXPECT_GT(n, previous);
    EXPECT_GT(n, k);  // more samples than occupied bins
    previous = n;
  }
  EXPECT_LT(cl::kld_sample_count(100, 0.1, 2.326), cl::kld_sample_count(100, 0.05, 2.326));
}

TEST(Resampling, OccupiedBinsCountsDistinctCells) {
  cl::ParticleSet particles(4);
  particles[0].state = {0.1, 0.1, 1, 0, 0, 0.01};
  particles[1].state = {0.2, 0.3, 1, 0, 0, 0.02};  // same bin as 0
  particles[2].state = {0.7, 0.1, 1, 0, 0, 0.01};  // next x bin
  particles[3].state = {0.1, 0.1, 1, 0, 0, 1.0};   // other yaw bin
  const std::vector<std::size_t> all{0, 1, 2, 3};
  EXPECT_EQ(cl::count_occupied_bins(particles, all, {}), 3u);
  const std::vector<std::size_t> repeated{0, 0, 1};
  EXPECT_EQ(cl::count_occupied_bins(particles, repeated, {}), 1u);
}

namespace {

struct FilterFixture {
  conicloc::maps::PlaneMap map = ct::make_box_room();
  cl::FreeSpace free_space{map};
  cl::MotionModel motion{cl::MotionModelConfig{}, free_space};
};

// Gives every particle the log-weight −|pose − peak|²/(2σ²) over x, y and yaw (yaw σ in rad
// scaled as 1 rad ~ 1 m).
void weight_around(cl::ParticleSet& particles, double peak_x, double peak_y, double sigma) {
  std::vector<double> w;
  for (const auto& p : particles) {
    const double d2 = std::pow(p.state.x - peak_x, 2) + std::pow(p.state.y - peak_y, 2) +
                      std::pow(cl::angle_difference(p.state.yaw, 0.0), 2);
    w.push_back(-d2 / (2 * sigma * sigma));
  }
  cl::normalise_log_weights(w);
  for (std::size_t i = 0; i < particles.size(); ++i) particles[i].log_weight = w[i];
}

}  // namespace

TEST(ParticleFilter, KldCountStaysWithinMinAndMax) {
  FilterFixture f;
  cl::ParticleFilterConfig config;
  config.min_particles = 100;
  config.max_particles = 3000;
  cl::ParticleFilter filter(config, f.motion, f.free_space);
  std::mt19937_64 rng(7);
  // A peaked posterior occupies a few bins: the count drops to the minimum.
  filter.initialise_global(2000, rng);
  weight_around(filter.particles(), 5.0, 3.0, 0.05);
  ASSERT_TRUE(filter.resample_if_needed(rng));
  EXPECT_EQ(filter.particles().size(), config.min_particles);
  // A spread posterior over the whole room needs more than the maximum: clamped to it.
  filter.initialise_global(2000, rng);
  weight_around(filter.particles(), 5.0, 3.0, 1.0);
  ASSERT_TRUE(filter.resample_if_needed(rng));
  EXPECT_EQ(filter.particles().size(), config.max_particles);
  EXPECT_NEAR(cl::log_sum_exp([&] {
                std::vector<double> w;
                for (const auto& p : filter.particles()) w.push_back(p.log_weight);
                return w;
              }()),
              0.0, 1e-9);
}

TEST(ParticleFilter, AGlobalStartDrawsEachPositionForFourHeadings) {
  FilterFixture f;
  cl::ParticleFilterConfig config;
  ASSERT_EQ(config.headings_per_position, 4u);
  cl::ParticleFilter filter(config, f.motion, f.free_space);
  std::mt19937_64 rng(3);
  filter.initialise_global(1000, rng);
  const cl::ParticleSet& particles = filter.particles();
  ASSERT_EQ(particles.size(), 1000u);
  std::set<std::pair<double, double>> positions;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const cl::PoseState& s = particles[i].state;
    const cl::PoseState& lead = particles[i - i % 4].state;
    EXPECT_EQ(s.x, lead.x);
    EXPECT_EQ(s.y, lead.y);
    EXPECT_EQ(s.z, lead.z);
    // Uniform headings spread over the turn: the group's quarter turns.
    EXPECT_NEAR(std::abs(cl::angle_difference(s.yaw, lead.yaw)),
                i % 4 == 2   ? M_PI
                : i % 4 == 0 ? 0.0
                             : M_PI / 2.0,
                1e-9);
    positions.insert({s.x, s.y});
  }
  EXPECT_EQ(positions.size(), 250u);
  // One heading per position: as many positions as particles.
  config.headings_per_position = 1;
  cl::ParticleFilter single(config, f.motion, f.free_space);
  single.initialise_global(1000, rng);
  positions.clear();
  for (const cl::Particle& p : single.particles()) positions.insert({p.state.x, p.state.y});
  EXPECT_EQ(positions.size(), 1000u);
}

TEST(ParticleFilter, SearchingUntilOneTightModeHoldsNearlyAllTheWeight) {
  FilterFixture f;
  cl::ParticleFilter filter(cl::ParticleFilterConfig{}, f.motion, f.free_space);
  // 1,000 particles: `far` of them 6 m away, the rest within 5 cm of (2, 3) and 5° of heading 0;
  // equal weights.
  const auto cloud = [&](int far) {
    std::mt19937_64 rng(11);
    std::normal_distribution<double> normal(0.0, 1.0);
    cl::ParticleSet& particles = filter.particles();
    particles.assign(1000, cl::Particle{});
    for (int i = 0; i < 1000; ++i) {
      const bool away = i < far;
      particles[i].state.x = (away ? 8.0 : 2.0) + 0.05 * normal(rng);
      particles[i].state.y = 3.0 + 0.05 * normal(rng);
      particles[i].state.yaw = 5.0 * M_PI / 180.0 * normal(rng);
      particles[i].log_weight = -std::log(1000.0);
    }
  };
  cloud(0);
  EXPECT_FALSE(filter.searching());  // one tight mode
  cloud(30);
  // 3 % six metres away spreads the cloud to ~1 m, yet one tight mode holds 97 %.
  EXPECT_GT(filter.position_spread_m(), 0.25);
  EXPECT_FALSE(filter.searching());
  cloud(100);  // 10 % elsewhere: two hypotheses
  EXPECT_TRUE(filter.searching());
  // One place on two storeys, half the weight on each: one xy, two hypotheses.
  cloud(0);
  for (int i = 0; i < 500; ++i) filter.particles()[static_cast<std::size_t>(i)].state.z += 3.4;
  EXPECT_NEAR(filter.position_spread_m(), std::hypot(0.05 * std::sqrt(2.0), 1.7), 0.02);
  EXPECT_TRUE(filter.searching());
  // One mode, but wide: still searching.
  std::mt19937_64 rng(5);
  filter.initialise_global(1000, rng);
  EXPECT_TRUE(filter.searching());
}

namespace {
// One term whose log-likelihood is a Gaussian peak of σ = 2 mm about (2, 3), heading 0 (1 rad
// scaled as 1 m): far narrower than a cloud a few cm wide.
class NarrowPeakModel final : public cl::ObservationModel {
 public:
  std::string name() const override { return "narrow-peak"; }
  void prepare(const conicloc::sensor::Scan&, const Eigen::AlignedBox3d&) override {}
  std::size_t term_count() const override { return 1; }
  void set_pose_blur(double) override {}
  cl::ObservationScore score(const cl::Pose3& T_map_sensor, Scratch*) const override {
    const Eigen::Vector3d t = T_map_sensor.translation();
    const Eigen::Matrix3d R = T_map_sensor.linear();
    const double yaw = std::atan2(R(1, 0), R(0, 0));
    const double d2 = std::pow(t.x() - 2.0, 2) + std::pow(t.y() - 3.0, 2) + yaw * yaw;
    return {-d2 / (2.0 * 4e-6), 1.0};
  }
};
}  // namespace

TEST(ParticleFilter, ATrackedCloudKeepsItsFloorOfEffectiveParticlesUnderANarrowPeak) {
  // 1,000 particles within 5 cm and 3° of the peak: one tight mode, so not searching(); under
  // the full exponent the 2 mm peak leaves a couple of particles to stand for the pose.
  FilterFixture f;
  const auto weighed = [&](double floor_fraction) {
    cl::ParticleFilterConfig config;
    config.tracking_ess_fraction = floor_fraction;
    cl::ParticleFilter filter(config, f.motion, f.free_space);
    std::mt19937_64 rng(5);
    cl::PoseState mean;
    mean.x = 2.0, mean.y = 3.0, mean.z = 1.2;
    cl::Vector6 sigma;
    sigma << 0.05, 0.05, 0.0, 0.0, 0.0, 0.05;
    filter.initialise_at(mean, sigma, 1000, rng);
    EXPECT_FALSE(filter.searching());
    NarrowPeakModel model;
    std::vector<std::unique_ptr<cl::ObservationModel::Scratch>> scratches(2);
    return filter.weight(model, scratches);
  };
  const cl::WeightSummary full = weighed(0.0);
  EXPECT_LT(full.ess, 5.0);  // of 1,000
  EXPECT_EQ(full.tempering, full.max_tempering);
  const cl::WeightSummary floored = weighed(0.05);
  // Uniform prior weights: the conditional ESS is the ESS, kept at the floor by bisection.
  EXPECT_GE(floored.ess, 0.05 * 1000.0);
  EXPECT_LT(floored.ess, 0.06 * 1000.0);  // and tempered no further than that
  EXPECT_LT(floored.tempering, 0.1 * floored.max_tempering);
}

TEST(ParticleFilter, ResamplesOnlyWhenEssFallsBelowThreshold) {
  FilterFixture f;
  cl::ParticleFilter filter(cl::ParticleFilterConfig{}, f.motion, f.free_space);
  std::mt19937_64 rng(3);
  filter.initialise_global(500, rng);
  EXPECT_FALSE(filter.resample_if_needed(rng));  // uniform: ESS = N
  weight_around(filter.particles(), 5.0, 3.0, 0.05);
  EXPECT_TRUE(filter.resample_if_needed(rng));
}

TEST(ParticleFilter, GlobalInitialisationLiesInsideNavigableCellsOnEveryStorey) {
  conicloc::maps::PlaneMap map;
  map.storeys = {{"ground", 0.0, 3.0}, {"first", 3.5, 6.5}};
  const auto add_cell = [&](conicloc::maps::Ring2 footprint, double floor_z, bool navigable) {
    conicloc::maps::Cell cell;
    cell.footprint = std::move(footprint);
    cell.floor_z = floor_z;
    cell.navigable = navigable;
    cell.storey = floor_z > 1.0 ? 1 : 0;
    map.cells.push_back(cell);
  };
  add_cell({{0, 0}, {4, 0}, {4, 3}, {0, 3}}, 0.0, true);                  // 12 m²
  add_cell({{0, 0}, {4, 0}, {4, 3}, {2, 3}, {2, 1}, {0, 1}}, 3.5, true);  // L shape, 8 m²
  add_cell({{10, 10}, {12, 10}, {12, 12}, {10, 12}}, 0.0, false);         // not navigable
  cl::FreeSpace free_space(map);
  EXPECT_NEAR(free_space.total_area_m2(), 20.0, 1e-9);
  cl::MotionModelConfig motion_config;
  motion_config.height_above_floor_m = 1.2;
  cl::MotionModel motion(motion_config, free_space);
  cl::ParticleFilter filter(cl::ParticleFilterConfig{}, motion, free_space);
  std::mt19937_64 rng(11);
  filter.initialise_global(4000, rng);
  ASSERT_EQ(filter.particles().size(), 4000u);
  int upstairs = 0;
  for (const auto& p : filter.particles()) {
    ASSERT_GE(p.cell, 0);
    ASSERT_LT(p.cell, 2);
    EXPECT_TRUE(conicloc::maps::ring_contains(map.cells[p.cell].footprint, {p.state.x, p.state.y}));
    EXPECT_NEAR(p.state.z, map.cells[p.cell].floor_z + 1.2, 1e-12);
    EXPECT_GT(p.state.yaw, -M_PI - 1e-12);
    EXPECT_LE(p.state.yaw, M_PI);
    upstairs += p.cell == 1 ? 1 : 0;
    // The cell found from the pose agrees with the sampled one (upper floor over x < 2, y < 1
    // is outside the L, so the ground cell is found there).
    EXPECT_EQ(free_space.cell_at(p.state.x, p.state.y, p.state.z - 1.2), p.cell);
  }
  // Area-proportional: 8/20 of the particles upstairs (binomial σ ≈ 31).
  EXPECT_NEAR(upstairs, 1600, 130);
}

TEST(ParticleFilter, InitialisationIsRepeatableWithTheSameSeed) {
  FilterFixture f;
  cl::ParticleFilter a(cl::ParticleFilterConfig{}, f.motion, f.free_space);
  cl::ParticleFilter b(cl::ParticleFilterConfig{}, f.motion, f.free_space);
  std::mt19937_64 rng_a(42), rng_b(42), rng_c(43);
  a.initialise_global(300, rng_a);
  b.initialise_global(300, rng_b);
  for (std::size_t i = 0; i < 300; ++i) {
    EXPECT_EQ(a.particles()[i].state.x, b.particles()[i].state.x);
    EXPECT_EQ(a.particles()[i].state.yaw, b.particles()[i].state.yaw);
  }
  b.initialise_global(300, rng_c);
  EXPECT_NE(a.particles()[0].state.x, b.particles()[0].state.x);
}

TEST(MotionModel, MovesInTheParticleFrameAndKeepsTheMountingHeight) {
  FilterFixture f;
  cl::MotionModel motion(ct::noiseless_motion(1.5), f.free_space);
  cl::ParticleSet particles(1);
  particles[0].state = {2.0, 3.0, 1.9, 0.0, 0.0, M_PI / 2};
  std::mt19937_64 rng(1);
  // 1 m forward and a quarter turn left, in the sensor frame: heading +y → moves to (2, 4).
  motion.predict(particles, cl::make_pose(1.0, 0.0, 0.0, M_PI / 2), 0.1, rng);
  EXPECT_NEAR(particles[0].state.x, 2.0, 1e-12);
  EXPECT_NEAR(particles[0].state.y, 4.0, 1e-12);
  EXPECT_NEAR(std::abs(particles[0].state.yaw), M_PI, 1e-12);
  EXPECT_EQ(particles[0].cell, 0);
  // z is pulled half way toward floor + 1.5 = 1.5.
  EXPECT_NEAR(particles[0].state.z, 1.7, 1e-12);
}

TEST(RelativeMotion, ScalingComposesAndInverts) {
  const cl::Pose3 motion = cl::make_pose(0.4, 0.1, 0.0, 0.3);
  const cl::Pose3 half = cl::scale_motion(motion, 0.5);
  EXPECT_NEAR(cl::yaw_of(half), 0.15, 1e-12);
  EXPECT_TRUE((cl::scale_motion(motion, -1.0) * cl::scale_motion(motion, 1.0))
                  .isApprox(cl::Pose3::Identity(), 1e-12));
  EXPECT_TRUE(cl::scale_motion(motion, 1.0).isApprox(motion, 1e-12));
  EXPECT_TRUE(
      (cl::scale_motion(motion, 0.3) * cl::scale_motion(motion, 0.7)).isApprox(motion, 1e-12));
  EXPECT_TRUE(cl::scale_motion(cl::Pose3::Identity(), 0.5).isApprox(cl::Pose3::Identity(), 1e-15));
  // A pure rotation about a tilted axis stays one.
  cl::Pose3 tilted = cl::Pose3::Identity();
  tilted.linear() =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(0.1, 0.2, 1).normalized()).toRotationMatrix();
  EXPECT_NEAR(cl::scale_motion(tilted, 0.25).translation().norm(), 0.0, 1e-15);
}

TEST(RelativeMotion, ASeventhOfTheMotionSevenTimesIsTheMotion) {
  // exp(f·log T) from the logarithm taken once: composing at(1/7) seven times gives T back, for
  // screw motions with large, small, tiny (the Taylor branch) and no rotation.
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  for (const double angle : {2.0, 0.3, 1e-3, 1e-8, 0.0}) {
    cl::Pose3 motion = cl::Pose3::Identity();
    motion.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    motion.translation() = Eigen::Vector3d(0.4, -0.1, 0.05);
    const cl::ConstantVelocityMotion velocity(motion);
    cl::Pose3 composed = cl::Pose3::Identity();
    for (int i = 0; i < 7; ++i) composed = composed * velocity.at(1.0 / 7.0);
    EXPECT_TRUE(composed.isApprox(motion, 1e-12)) << angle;
    EXPECT_TRUE(velocity.at(0.0).isApprox(cl::Pose3::Identity(), 1e-15)) << angle;
    EXPECT_TRUE((velocity.at(-0.4) * velocity.at(0.4)).isApprox(cl::Pose3::Identity(), 1e-12))
        << angle;
  }
}

TEST(RelativeMotion, TheTabulatedMotionMovesAPointAsTheScrewMotionDoes) {
  // The chords within 1.25e-9 rad of the rotation (1.24e-7 m at 99 m) and 1e-8 m of the
  // translation; the knots themselves are exact. A turn of 2 rad would take 20,000 knots: the
  // exact motion instead.
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> fraction(-1.0, 0.0);
  for (const double angle : {2.0, 0.15, 0.05, 1e-3, 0.0}) {
    cl::Pose3 motion = cl::Pose3::Identity();
    motion.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    motion.translation() = Eigen::Vector3d(0.4, -0.1, 0.05);
    const cl::ConstantVelocityMotion exact(motion);
    const cl::TabulatedMotion table(exact, -1.0, 0.0);
    const Eigen::Vector3d p(70.0, -70.0, 5.0);  // 99 m out
    for (int i = 0; i < 2000; ++i) {
      const double f = i == 0 ? -1.0 : i == 1 ? 0.0 : fraction(rng);
      EXPECT_LT((table.apply(f, p) - exact.at(f) * p).norm(), 1.34e-7) << angle << " at " << f;
      EXPECT_NEAR(table.yaw(f), cl::yaw_of(exact.at(f)), 1.25e-9) << angle << " at " << f;
      EXPECT_LT((table.apply(f, Eigen::Vector3d::Zero()) - exact.at(f).translation()).norm(),
                1.01e-8)
          << angle << " at " << f;
    }
    // A return time that is not a number moves its point to no number, as the exact motion does;
    // a span without a number, or of one fraction, takes the exact motion.
    EXPECT_TRUE(table.apply(std::nan(""), p).hasNaN());
    EXPECT_TRUE(cl::TabulatedMotion(exact, std::nan(""), 0.0).apply(-0.3, p).isApprox(
        exact.at(-0.3) * p, 1e-15));
    EXPECT_TRUE(cl::TabulatedMotion(exact, -0.3, -0.3).apply(-0.3, p).isApprox(
        exact.at(-0.3) * p, 1e-15));
  }
}

TEST(Deskew, ReturnsOfAMovingSensorLandWhereTheReferencePoseSeesThem) {
  // The sensor moves 0.1 m along x during one rotation; de-skewed to the scan end, each point
  // must lie on the room's walls seen from the end pose.
  const auto map = ct::make_box_room();
  const cl::Pose3 start = cl::make_pose(3.0, 3.0, 1.2, 0.2);
  const cl::Pose3 motion = cl::make_pose(0.1, 0.0, 0.0, 0.05);
  const cl::Pose3 end = start * motion;
  const auto calibration =
      conicloc::sensor::builtin_calibration(conicloc::sensor::SensorModel::VLP16);
  conicloc::sensor::Scan scan;
  scan.start_time_s = 0.0;
  scan.end_time_s = 0.1;
  scan.rings.resize(16);
  for (const auto& laser : calibration.lasers) {
    auto& ring = scan.rings[laser.ring];
    ring.ring = laser.ring;
    ring.elevation_rad = laser.elevation_rad;
    ring.vertical_offset_m = laser.vertical_offset_m;
    for (int s = 0; s < 360; s += 3) {
      const double t = 0.1 * s / 360.0;
      const cl::Pose3 T_map_firing = start * cl::scale_motion(motion, t / 0.1);
      const double azimuth = s * M_PI / 180.0;
      const Eigen::Vector3d d(std::cos(laser.elevation_rad) * std::cos(azimuth),
                              std::cos(laser.elevation_rad) * std::sin(azimuth),
                              std::sin(laser.elevation_rad));
      conicloc::sensor::Return ret;
      ret.azimuth_rad = azimuth;
      ret.time_s = t;
      ret.range_m = ct::cast_ray(map, T_map_firing * Eigen::Vector3d(0, 0, laser.vertical_offset_m),
                                 T_map_firing.linear() * d);
      ring.returns.push_back(ret);
    }
  }
  const auto fixed = cl::deskew_scan(scan, motion, 0.1, 0.1);
  int wall_returns = 0, raw_off = 0, fixed_off = 0;
  for (std::size_t r = 0; r < 16; ++r) {
    const auto& ring = fixed.rings[r];
    ASSERT_TRUE(
        std::is_sorted(ring.returns.begin(), ring.returns.end(),
                       [](const auto& a, const auto& b) { return a.azimuth_rad < b.azimuth_rad; }));
    const auto horizontal_error = [&](const conicloc::sensor::RingScan& rs,
                                      const conicloc::sensor::Return& ret) {
      // Horizontal range the end pose predicts along the return's azimuth vs. the measured.
      const Eigen::Vector3d d(std::cos(rs.elevation_rad) * std::cos(ret.azimuth_rad),
                              std::cos(rs.elevation_rad) * std::sin(ret.azimuth_rad),
                              std::sin(rs.elevation_rad));
      const double predicted =
          ct::cast_ray(map, end * Eigen::Vector3d(0, 0, rs.vertical_offset_m), end.linear() * d);
      return std::abs(predicted - ret.range_m) * std::cos(rs.elevation_rad);
    };
    for (std::size_t i = 0; i < ring.returns.size(); ++i) {
      // Walls only: skip returns that hit floor or ceiling.
      const Eigen::Vector3d p = end * conicloc::sensor::sensor_point(ring, ring.returns[i]);
      if (p.z() < 0.05 || p.z() > 2.95) continue;
      ++wall_returns;
      fixed_off += horizontal_error(ring, ring.returns[i]) > 0.002 ? 1 : 0;
      raw_off += horizontal_error(scan.rings[r], scan.rings[r].returns[i]) > 0.002 ? 1 : 0;
    }
  }
  ASSERT_GT(wall_returns, 500);
  EXPECT_GT(raw_off, wall_returns / 2);  // the skew is visible on most wall returns ...
  // ... and gone, but for the few beams the azimuth shift moves across a corner or pillar edge.
  EXPECT_LT(fixed_off, wall_returns / 50);
  // Workers of their own move the rings: any count gives the same scan, to the last bit.
  for (const int threads : {2, 3, 16}) {
    const auto threaded = cl::deskew_scan(scan, motion, 0.1, 0.1, threads);
    for (std::size_t r = 0; r < 16; ++r) {
      ASSERT_EQ(threaded.rings[r].returns.size(), fixed.rings[r].returns.size());
      for (std::size_t i = 0; i < fixed.rings[r].returns.size(); ++i) {
        EXPECT_EQ(threaded.rings[r].returns[i].azimuth_rad, fixed.rings[r].returns[i].azimuth_rad);
        EXPECT_EQ(threaded.rings[r].returns[i].range_m, fixed.rings[r].returns[i].range_m);
        EXPECT_EQ(threaded.rings[r].returns[i].time_s, fixed.rings[r].returns[i].time_s);
      }
    }
  }
  // Into a scan kept from before (another scan's rings, more of them, longer and shorter): the
  // same scan, nothing of the old one left.
  conicloc::sensor::Scan kept = fixed;
  kept.rings.push_back(kept.rings.front());
  kept.rings[0].returns.resize(kept.rings[0].returns.size() * 2);
  kept.rings[1].returns.resize(3);
  kept.index = 99;
  cl::deskew_scan_into(scan, motion, 0.1, 0.1, 2, kept);
  // And in place: the scan itself de-skewed.
  conicloc::sensor::Scan in_place = scan;
  cl::deskew_scan_into(in_place, motion, 0.1, 0.1, 2, in_place);
  for (const conicloc::sensor::Scan* into : {&kept, &in_place}) {
    EXPECT_EQ(into->index, scan.index);
    EXPECT_EQ(into->end_time_s, fixed.end_time_s);
    ASSERT_EQ(into->rings.size(), fixed.rings.size());
    for (std::size_t r = 0; r < fixed.rings.size(); ++r) {
      EXPECT_EQ(into->rings[r].elevation_rad, fixed.rings[r].elevation_rad);
      ASSERT_EQ(into->rings[r].returns.size(), fixed.rings[r].returns.size());
      for (std::size_t i = 0; i < fixed.rings[r].returns.size(); ++i) {
        const auto& a = into->rings[r].returns[i];
        const auto& b = fixed.rings[r].returns[i];
        EXPECT_EQ(a.azimuth_rad, b.azimuth_rad);
        EXPECT_EQ(a.range_m, b.range_m);
        EXPECT_EQ(a.time_s, b.time_s);
        EXPECT_EQ(a.status, b.status);
      }
    }
  }
}

TEST(PoseEstimate, MeanOfTheStrongestModeNotBetweenModes) {
  cl::ParticleSet particles;
  const auto add = [&](double x, double yaw, double weight) {
    cl::Particle p;
    p.state = {x, 0.0, 1.0, 0.0, 0.0, yaw};
    p.log_weight = std::log(weight);
    particles.push_back(p);
  };
  add(1.0, M_PI - 0.01, 0.3);
  add(1.2, -M_PI + 0.03, 0.3);  // wraps: the mode's yaw mean is π + 0.01
  add(8.0, 0.0, 0.25);
  add(8.1, 0.0, 0.15);
  // Either anchor: the heaviest particle starts the mode that also holds the most weight.
  for (const auto anchor : {cl::ModeAnchor::HeaviestParticle, cl::ModeAnchor::MostWeight}) {
    const auto estimate = cl::estimate_pose(particles, {}, anchor);
    EXPECT_NEAR(estimate.state.x, 1.1, 1e-12);
    EXPECT_NEAR(std::abs(cl::angle_difference(estimate.state.yaw, M_PI + 0.01)), 0.0, 1e-12);
    EXPECT_NEAR(estimate.mode_weight, 0.6, 1e-12);
    EXPECT_GT(estimate.covariance(0, 0), 9.0);  // the whole set's spread about the mode
  }
}

TEST(PoseEstimate, OnePlaceOnTwoStoreysIsTwoModesNotAPoseInTheSlab) {
  // Identical storeys 3.41 m apart (a global start's plan search finds both): the estimate is
  // one storey's height, not their mean between them, and the covariance shows the other.
  cl::ParticleSet particles;
  const auto add = [&](double x, double z, double weight) {
    cl::Particle p;
    p.state = {x, 2.0, z, 0.0, 0.0, 1.3};
    p.log_weight = std::log(weight);
    particles.push_back(p);
  };
  add(16.40, 0.80, 0.26);
  add(16.45, 0.80, 0.22);
  add(16.41, 4.21, 0.25);
  add(16.43, 4.21, 0.27);
  for (const auto anchor : {cl::ModeAnchor::HeaviestParticle, cl::ModeAnchor::MostWeight}) {
    const auto estimate = cl::estimate_pose(particles, {}, anchor);
    EXPECT_NEAR(estimate.state.z, 4.21, 1e-12);
    EXPECT_NEAR(estimate.mode_weight, 0.52, 1e-12);
    EXPECT_NEAR(estimate.covariance(2, 2), 0.48 * 3.41 * 3.41, 1e-9);
  }
}

TEST(PoseEstimate, TheModeHoldingTheMostWeightNotTheHeaviestParticle) {
  // Just after a restart: 100 kept particles of the tracked pose around (2, 3), and one lone
  // particle 80 m away that fitted the scan 20 times better than any one of them.
  cl::ParticleSet particles;
  const auto add = [&](double x, double y, double weight) {
    cl::Particle p;
    p.state = {x, y, 1.0, 0.0, 0.0, 0.5};
    p.log_weight = std::log(weight);
    particles.push_back(p);
  };
  add(82.0, 3.0, 20.0);
  for (int i = 0; i < 100; ++i) add(2.0 + 0.001 * i, 3.0, 1.0);
  const auto estimate = cl::estimate_pose(particles, {}, cl::ModeAnchor::MostWeight);
  EXPECT_NEAR(estimate.state.x, 2.0495, 1e-9);
  EXPECT_NEAR(estimate.mode_weight, 100.0 / 120.0, 1e-12);
  // Around the heaviest particle (a tracked cloud's peak): the lone one.
  EXPECT_NEAR(cl::estimate_pose(particles).state.x, 82.0, 1e-12);
}
