// Runner-up hypotheses kept through resampling while a (re)start's cloud settles
// (runner_up_hypotheses.hpp): modes found, their share of the weight kept, their particles kept,
// dropped under the floor, and roughened by their own extent.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "localizer/filter/free_space.hpp"
#include "localizer/filter/log_weights.hpp"
#include "localizer/filter/motion_model.hpp"
#include "localizer/filter/particle_filter.hpp"
#include "localizer/filter/runner_up_hypotheses.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

/// Resamples whatever the ESS (the clusters' equal weights would not ask for it).
cl::ParticleFilterConfig always_resampling() {
  cl::ParticleFilterConfig config;  // 200 particles at least, 50 per kept runner-up
  config.resample_ess_fraction = 2.0;
  return config;
}

struct Room {
  conicloc::maps::PlaneMap map = ct::make_box_room();  // 10 m × 6 m
  cl::FreeSpace free_space{map};
  cl::MotionModel motion{cl::MotionModelConfig{}, free_space};
};

/// `count` particles within ±2 cm of (x, y), heading 0, at the mounting height.
void add_cluster(cl::ParticleSet& particles, double x, double y, int count, double mass) {
  for (int i = 0; i < count; ++i) {
    cl::Particle p;
    p.state.x = x + 0.04 * (i % 5) / 4.0 - 0.02;
    p.state.y = y + 0.04 * (i / 5 % 5) / 4.0 - 0.02;
    p.state.z = 0.8;
    p.cell = 0;
    p.log_weight = std::log(mass / count);
    particles.push_back(p);
  }
}

double mass_near(const cl::ParticleSet& particles, double x, double y) {
  double mass = 0.0;
  for (const cl::Particle& p : particles)
    if (std::hypot(p.state.x - x, p.state.y - y) < 0.5) mass += std::exp(p.log_weight);
  return mass;
}

int count_near(const cl::ParticleSet& particles, double x, double y) {
  int count = 0;
  for (const cl::Particle& p : particles)
    if (std::hypot(p.state.x - x, p.state.y - y) < 0.5) ++count;
  return count;
}

}  // namespace

TEST(FindModes, GathersHeaviestFirstAndStopsUnderTheFloor) {
  cl::ParticleSet particles;
  add_cluster(particles, 2.0, 2.0, 100, 0.9);
  add_cluster(particles, 8.0, 4.0, 25, 0.09);
  add_cluster(particles, 5.0, 1.0, 10, 0.01 - 1e-6);
  add_cluster(particles, 1.0, 5.0, 1, 1e-6);  // under the floor
  const cl::Modes modes = cl::find_modes(particles, {}, 8, 1e-4);
  ASSERT_EQ(modes.weight.size(), 3u);
  EXPECT_NEAR(modes.weight[0], 0.9, 1e-12);
  EXPECT_NEAR(modes.weight[1], 0.09, 1e-12);
  EXPECT_NEAR(modes.weight[2], 0.01 - 1e-6, 1e-12);
  EXPECT_EQ(modes.mode_of.front(), 0);
  EXPECT_EQ(modes.mode_of[100], 1);
  EXPECT_EQ(modes.mode_of[125], 2);
  EXPECT_EQ(modes.mode_of.back(), -1);
  // At most max_modes.
  EXPECT_EQ(cl::find_modes(particles, {}, 2, 1e-4).weight.size(), 2u);
}

TEST(RunnerUpResampling, ARunnerUpKeepsItsShareAndItsParticles) {
  Room room;
  cl::ParticleFilter filter(always_resampling(), room.motion, room.free_space);
  const auto cloud = [&] {
    cl::ParticleSet& particles = filter.particles();
    particles.clear();
    add_cluster(particles, 2.0, 2.0, 1000, 0.999);
    add_cluster(particles, 8.0, 4.0, 25, 0.001);
  };
  std::mt19937_64 rng(3);
  // Proportional resampling to the KLD count keeps about 0.001 × 200 of the runner-up: none.
  cloud();
  ASSERT_TRUE(filter.resample_if_needed(rng, false));
  EXPECT_LE(count_near(filter.particles(), 8.0, 4.0), 1);
  // Kept: 50 copies holding its 0.1 %, the leader's count and share unchanged.
  cloud();
  ASSERT_TRUE(filter.resample_if_needed(rng, true));
  const cl::ParticleSet& kept = filter.particles();
  EXPECT_EQ(count_near(kept, 8.0, 4.0), 50);
  EXPECT_EQ(count_near(kept, 2.0, 2.0), 200);
  EXPECT_NEAR(mass_near(kept, 8.0, 4.0), 0.001, 1e-12);
  EXPECT_NEAR(mass_near(kept, 2.0, 2.0), 0.999, 1e-12);
  std::vector<double> weights;
  for (const cl::Particle& p : kept) weights.push_back(p.log_weight);
  EXPECT_NEAR(cl::log_sum_exp(weights), 0.0, 1e-12);
}

TEST(RunnerUpResampling, ARunnerUpUnderTheFloorIsDropped) {
  Room room;
  cl::ParticleFilter filter(always_resampling(), room.motion, room.free_space);
  add_cluster(filter.particles(), 2.0, 2.0, 1000, 1.0 - 1e-5);
  add_cluster(filter.particles(), 8.0, 4.0, 25, 1e-5);  // under min_weight 1e-4
  std::mt19937_64 rng(3);
  ASSERT_TRUE(filter.resample_if_needed(rng, true));
  EXPECT_EQ(count_near(filter.particles(), 8.0, 4.0), 0);
}

TEST(RunnerUpResampling, ARunnerUpWithEnoughWeightIsResampledInProportion) {
  Room room;
  cl::ParticleFilter filter(always_resampling(), room.motion, room.free_space);
  add_cluster(filter.particles(), 2.0, 2.0, 1000, 0.6);
  add_cluster(filter.particles(), 8.0, 4.0, 25, 0.4);  // 0.4 of at least 200 particles ≥ 50
  // Labels of an earlier resampling that kept it apart: proportional now, they are cleared.
  for (std::size_t i = 1000; i < filter.particles().size(); ++i) filter.particles()[i].hypothesis = 1;
  std::mt19937_64 rng(3);
  ASSERT_TRUE(filter.resample_if_needed(rng, true));
  const cl::ParticleSet& particles = filter.particles();
  const double uniform = -std::log(static_cast<double>(particles.size()));
  for (const cl::Particle& p : particles) {
    EXPECT_NEAR(p.log_weight, uniform, 1e-12);
    EXPECT_EQ(p.hypothesis, 0);
  }
}

TEST(RunnerUpResampling, RougheningJittersEachHypothesisByItsOwnExtent) {
  Room room;
  cl::ParticleFilter filter(always_resampling(), room.motion, room.free_space);
  std::mt19937_64 rng(5);
  // The leader spans 4 cm; a runner-up 6.3 m away. Jittered by the whole cloud's extent, the
  // leader's particles would move by σ = 0.1 · 6 m / ∛250 ≈ 10 cm.
  add_cluster(filter.particles(), 2.0, 2.0, 1000, 0.999);
  add_cluster(filter.particles(), 8.0, 4.0, 25, 0.001);
  ASSERT_TRUE(filter.resample_if_needed(rng, true));
  filter.roughen(rng);
  for (const cl::Particle& p : filter.particles()) {
    const bool leader = p.hypothesis == 0;
    EXPECT_LT(std::hypot(p.state.x - (leader ? 2.0 : 8.0), p.state.y - (leader ? 2.0 : 4.0)),
              0.05);
  }
}
