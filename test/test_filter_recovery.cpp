// The filter's own motion estimate without odometry (particle velocities) and its recovery mix
// (keep the tracked hypothesis, search near the last good pose, then the whole building).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "localizer/filter/free_space.hpp"
#include "localizer/filter/hypothesis_velocities.hpp"
#include "localizer/filter/log_weights.hpp"
#include "localizer/filter/motion_model.hpp"
#include "localizer/filter/particle_filter.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {
/// Noiseless velocity motion in the box room, velocities reverting with T = 0.5 s.
struct RevertingMotion {
  static cl::MotionModelConfig config() {
    auto config = ct::noiseless_motion(1.2);
    config.velocity_correlation_s = 0.5;
    return config;
  }
  conicloc::maps::PlaneMap map = ct::make_box_room();
  cl::FreeSpace free_space{map};
  cl::MotionModel motion{config(), free_space};
};
}  // namespace

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
  const RevertingMotion room;
  const cl::MotionModel& motion = room.motion;
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

TEST(VelocityMotion, EachHypothesisRevertsToItsOwnMeanVelocity) {
  // A restart's cloud: the true place, its particles moving at 1 m/s, and another place 20 m
  // off, at rest and three times as heavy; one lone particle beyond the modes kept.
  cl::ParticleSet particles;
  const auto add = [&](double x, double vx, double weight) {
    cl::Particle p;
    p.state = {x, 3.0, 1.2, 0.0, 0.0, 0.0};
    p.velocity_x = vx;
    p.log_weight = std::log(weight);
    particles.push_back(p);
  };
  add(2.0, 0.9, 0.1), add(2.3, 1.1, 0.1), add(2.6, 1.0, 0.05);  // mean 1.0 over 0.25
  add(22.0, 0.0, 0.3), add(22.5, 0.2, 0.3);                     // mean 0.1 over 0.6
  add(50.0, 0.7, 0.08);  // lighter than the particles the two places' modes gather around
  particles[0].yaw_rate = 0.3, particles[1].yaw_rate = 0.1;  // the moving place turns too
  particles[5].yaw_rate = -0.2;
  std::vector<double> log_weights;
  for (const auto& p : particles) log_weights.push_back(p.log_weight);
  cl::normalise_log_weights(log_weights);
  for (std::size_t i = 0; i < particles.size(); ++i) particles[i].log_weight = log_weights[i];

  const auto means = cl::hypothesis_velocities(particles, {}, 2);
  ASSERT_EQ(means.size(), particles.size());
  for (int i : {0, 1, 2}) {
    EXPECT_NEAR(means[i].x(), (0.09 + 0.11 + 0.05) / 0.25, 1e-12);
    EXPECT_NEAR(means[i].z(), (0.03 + 0.01) / 0.25, 1e-12);  // its yaw rate
  }
  for (int i : {3, 4}) EXPECT_NEAR(means[i].x(), 0.06 / 0.6, 1e-12);
  EXPECT_DOUBLE_EQ(means[5].x(), 0.7);  // a hypothesis of its own: no pull at all
  EXPECT_DOUBLE_EQ(means[5].z(), -0.2);

  // Stepped about these means the moving place keeps its speed; about the cloud's mean
  // (0.39 m/s) it would lose a share 1 − e^(−dt/T) of the difference per scan.
  const RevertingMotion room;
  const cl::MotionModel& motion = room.motion;
  std::mt19937_64 rng(1);
  motion.predict_velocity(particles, std::span<const Eigen::Vector3d>(means), 0.1, rng);
  const double keep = std::exp(-0.1 / 0.5);
  EXPECT_NEAR(particles[0].velocity_x, 1.0 + keep * (0.9 - 1.0), 1e-12);
  EXPECT_NEAR(particles[4].velocity_x, 0.1 + keep * (0.2 - 0.1), 1e-12);
  EXPECT_DOUBLE_EQ(particles[5].velocity_x, 0.7);
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

// Without odometry a particle's position spreads only by what its velocity leaves open: the OU
// innovation of the step (σ_v·√(1 − e^(−2dt/T))·dt) and the acceleration within it
// (σ² = q·dt³/12, q = 2σ_v²/T), whatever the speed — not an odometer's 3 cm per scan, which
// drowned the velocity's effect on where a particle lands and kept the scans from selecting it.
TEST(VelocityMotion, APositionSpreadsOnlyByWhatItsVelocityLeavesOpen) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  cl::MotionModelConfig config;  // the defaults: σ_v = 0.3 m/s, T = 1 s
  config.height_above_floor_m = 1.2;
  const cl::MotionModel motion(config, free_space);
  const double dt = 0.1;
  const double innovation = 0.3 * std::sqrt(1.0 - std::exp(-2.0 * dt / 1.0)) * dt;    // 1.28 cm
  const double within_step = std::sqrt(2.0 * 0.3 * 0.3 / 1.0 * dt * dt * dt / 12.0);  // 3.9 mm
  const double expected = std::hypot(innovation, within_step);
  for (const double speed : {0.0, 1.5}) {
    cl::ParticleSet particles(4000);
    for (auto& p : particles) {
      p.state = {5.0, 3.0, 1.2, 0.0, 0.0, 0.0};  // facing +x: the particle's frame is the map's
      p.velocity_x = speed;                      // known: a tracked particle's
    }
    std::mt19937_64 rng(5);
    motion.predict_velocity(particles, Eigen::Vector3d(speed, 0.0, 0.0), dt, rng);
    double sx = 0.0, sx2 = 0.0, sy2 = 0.0;
    for (const auto& p : particles) {
      const double rx = p.state.x - 5.0 - speed * dt;  // beyond the velocity's own step
      const double ry = p.state.y - 3.0;
      sx += rx, sx2 += rx * rx, sy2 += ry * ry;
    }
    const double n = static_cast<double>(particles.size());
    // 4000 draws: the std. dev. is known to ~1.1 %, the mean to σ/63.
    EXPECT_NEAR(std::sqrt(sx2 / n - (sx / n) * (sx / n)), expected, 0.05 * expected) << speed;
    EXPECT_NEAR(std::sqrt(sy2 / n), expected, 0.05 * expected) << speed;
    EXPECT_NEAR(sx / n, 0.0, 0.1 * expected) << speed;
  }
}

// A new particle's velocity is open (1 m/s either way) rather than a draw: the first scan, which
// sees no displacement yet, cannot fix it (a resampling after it copies the open velocity, not a
// guess). The next step spreads the particles by what the velocity allows, and each then knows
// the velocity its displacement shows — the one the scan selects along with the position.
TEST(VelocityMotion, AVelocityNoScanHasSeenStaysOpenUntilADisplacementShowsIt) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  cl::MotionModelConfig config;
  config.height_above_floor_m = 1.2;
  config.initial_speed_sigma_m_s = 1.0;
  const cl::MotionModel motion(config, free_space);
  std::mt19937_64 rng(7);
  cl::ParticleSet particles(4000);
  for (auto& p : particles) {
    motion.draw_initial_velocity(p, rng);
    p.state = {5.0, 3.0, 1.2, 0.0, 0.0, 0.0};
  }
  // The first scan: no time has passed, nothing moved, nothing is known of the velocity.
  motion.predict_velocity(particles, Eigen::Vector3d::Zero(), 0.0, rng);
  for (const auto& p : particles) {
    ASSERT_EQ(p.velocity_x, 0.0);
    ASSERT_EQ(p.state.x, 5.0);
    ASSERT_DOUBLE_EQ(p.velocity_variance, 1.0);
  }
  const double dt = 0.1;
  motion.predict_velocity(particles, Eigen::Vector3d::Zero(), dt, rng);
  double dx2 = 0.0;
  for (const auto& p : particles) {
    const double dx = p.state.x - 5.0;
    dx2 += dx * dx;
    const double dy = p.state.y - 3.0;
    EXPECT_LE(std::hypot(dx, dy), config.max_speed_m_s * dt + 1e-12);  // the speed bound holds
    // The velocity is the displacement's, up to the acceleration within the step (4 mm / 0.1 s).
    EXPECT_NEAR(p.velocity_x, dx / dt, 0.05);
    EXPECT_NEAR(p.velocity_y, dy / dt, 0.05);
    EXPECT_LT(std::sqrt(p.velocity_variance), 0.05);
  }
  // The open velocity became the displacements' spread: ~0.9 m/s (1 m/s decayed over 0.1 s of
  // the OU's 1 s) × 0.1 s.
  const double spread = std::sqrt(dx2 / static_cast<double>(particles.size()));
  EXPECT_GT(spread, 0.08);
  EXPECT_LT(spread, 0.10);
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
