// The filter's own motion estimate without odometry (particle velocities) and its recovery mix
// (keep the tracked hypothesis, search near the last good pose, then the whole building).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "localizer/filter/free_space.hpp"
#include "localizer/filter/motion_model.hpp"
#include "localizer/filter/particle_filter.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

TEST(VelocityMotion, AParticleMovesByItsOwnVelocityInItsOwnFrame) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  const cl::MotionModel motion(ct::noiseless_motion(1.2), free_space);
  cl::ParticleSet particles(1);
  particles[0].state = {2.0, 3.0, 1.2, 0.0, 0.0, M_PI / 2};
  particles[0].velocity_x = 0.8;  // forward = +y on the map
  particles[0].velocity_y = 0.2;  // left = −x
  particles[0].yaw_rate = 0.5;
  std::mt19937_64 rng(1);
  // The mean equals the particle's velocity: the OU step leaves it unchanged.
  motion.predict_velocity(particles, Eigen::Vector3d(0.8, 0.2, 0.5), 0.1, rng);
  EXPECT_NEAR(particles[0].state.x, 2.0 - 0.02, 1e-12);
  EXPECT_NEAR(particles[0].state.y, 3.0 + 0.08, 1e-12);
  EXPECT_NEAR(particles[0].state.yaw, M_PI / 2 + 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(particles[0].velocity_x, 0.8);
  EXPECT_DOUBLE_EQ(particles[0].yaw_rate, 0.5);
}

TEST(VelocityMotion, VelocitiesRevertToTheCloudMeanAtTheConfiguredRate) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  auto config = ct::noiseless_motion(1.2);
  config.velocity_correlation_s = 0.5;
  const cl::MotionModel motion(config, free_space);
  cl::ParticleSet particles(1);
  particles[0].state = {2.0, 3.0, 1.2, 0.0, 0.0, 0.0};
  particles[0].velocity_x = 1.0;
  particles[0].yaw_rate = -0.4;
  std::mt19937_64 rng(1);
  motion.predict_velocity(particles, Eigen::Vector3d(0.2, 0.0, 0.0), 0.1, rng);
  const double keep = std::exp(-0.1 / 0.5);
  EXPECT_NEAR(particles[0].velocity_x, 0.2 + keep * 0.8, 1e-12);
  EXPECT_NEAR(particles[0].yaw_rate, -0.4 * keep, 1e-12);
  // It moved by the velocity after the step.
  EXPECT_NEAR(particles[0].state.x, 2.0 + 0.1 * (0.2 + keep * 0.8), 1e-12);
}

TEST(VelocityMotion, SpreadAboutTheMeanIsStationaryAtSigma) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  auto config = ct::noiseless_motion(1.2);
  config.velocity_sigma_m_s = 0.3;
  config.yaw_rate_sigma_rad_s = 0.2;
  const cl::MotionModel motion(config, free_space);
  cl::ParticleSet particles(4000);
  for (auto& p : particles) {
    p.state = {5.0, 3.0, 1.2, 0.0, 0.0, 0.0};
    p.velocity_x = 0.5;  // at the mean, with no spread
  }
  std::mt19937_64 rng(3);
  // 3 correlation times from zero spread; the spread approaches σ (1 − e^(−6) of its variance).
  for (int k = 0; k < 30; ++k) {
    motion.predict_velocity(particles, Eigen::Vector3d(0.5, 0.0, 0.0), 0.1, rng);
    for (auto& p : particles) p.state = {5.0, 3.0, 1.2, 0.0, 0.0, 0.0};  // stay in the room
  }
  double sum = 0.0, sum2 = 0.0, yaw2 = 0.0;
  for (const auto& p : particles) {
    sum += p.velocity_x, sum2 += p.velocity_x * p.velocity_x, yaw2 += p.yaw_rate * p.yaw_rate;
  }
  const double n = static_cast<double>(particles.size());
  EXPECT_NEAR(sum / n, 0.5, 0.02);
  EXPECT_NEAR(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 0.3, 0.015);
  EXPECT_NEAR(std::sqrt(yaw2 / n), 0.2, 0.01);
}

TEST(Recovery, RestartKeepsTheTrackedHypothesisAndSearchesNearTheLastGoodPoseFirst) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  const cl::MotionModel motion(cl::MotionModelConfig{}, free_space);
  cl::ParticleFilter filter(cl::ParticleFilterConfig{}, motion, free_space);
  std::mt19937_64 rng(11);
  const cl::PoseState tracked{7.0, 4.0, 1.0, 0.0, 0.0, 1.0};
  cl::Vector6 sigma = cl::Vector6::Zero();
  filter.initialise_at(tracked, sigma, 300, rng);
  cl::RestartMix mix;
  mix.keep_fraction = 0.2;
  mix.local_fraction = 0.5;
  mix.centre = {3.0, 2.5, 1.0, 0.0, 0.0, -0.5};
  mix.local_sigma_xy_m = 0.3;
  mix.local_sigma_yaw_rad = 0.1;
  filter.restart(1000, mix, rng);
  ASSERT_EQ(filter.particles().size(), 1000u);
  int kept = 0, local = 0;
  for (const auto& p : filter.particles()) {
    EXPECT_GE(p.cell, 0);  // every particle stands in a navigable cell
    EXPECT_NEAR(p.log_weight, -std::log(1000.0), 1e-12);
    if (p.state.x == tracked.x && p.state.y == tracked.y) ++kept;
    if (std::hypot(p.state.x - 3.0, p.state.y - 2.5) < 1.5 &&
        std::abs(cl::angle_difference(p.state.yaw, -0.5)) < 0.5)
      ++local;
  }
  EXPECT_EQ(kept, 200);
  // The local ones, plus the few global ones that fall there by chance.
  EXPECT_GE(local, 500);
  EXPECT_LT(local, 560);
}
