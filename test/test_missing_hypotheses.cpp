// The places a searching cloud lacks (missing_hypotheses.hpp): which of the plan search's
// candidates are missing, and how ParticleFilter::add_hypotheses adds them without touching the
// hypotheses the cloud holds.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "localizer/filter/free_space.hpp"
#include "localizer/filter/missing_hypotheses.hpp"
#include "localizer/filter/motion_model.hpp"
#include "localizer/filter/particle_filter.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace ct = conicloc::test;

namespace {

constexpr double kHeight = 0.8;  // the sensor's height over the floor in the first tests

/// `count` particles within ±2 cm of (x, y) at `yaw`, on the floor at z = 0, holding `mass`.
void add_cluster(cl::ParticleSet& particles, double x, double y, double yaw, int count,
                 double mass) {
  for (int i = 0; i < count; ++i) {
    cl::Particle p;
    p.state.x = x + 0.04 * (i % 5) / 4.0 - 0.02;
    p.state.y = y + 0.04 * (i / 5 % 5) / 4.0 - 0.02;
    p.state.z = kHeight;
    p.state.yaw = yaw;
    p.cell = 0;
    p.log_weight = std::log(mass / count);
    particles.push_back(p);
  }
}

cl::PlanCandidate candidate(double x, double y, double yaw, double score, double floor_z = 0.0) {
  cl::PlanCandidate c;
  c.x = x;
  c.y = y;
  c.yaw = yaw;
  c.score = score;
  c.floor_z = floor_z;
  return c;
}

std::vector<double> xs(const std::vector<cl::PlanCandidate>& candidates) {
  std::vector<double> out;
  for (const cl::PlanCandidate& c : candidates) out.push_back(c.x);
  return out;
}

}  // namespace

TEST(MissingHypotheses, TheCandidatesTheCloudHoldsLessThanTheFloorOf) {
  cl::ParticleSet particles;
  add_cluster(particles, 2.0, 2.0, 0.0, 100, 0.9);
  add_cluster(particles, 8.0, 4.0, 0.0, 25, 0.1 - 5e-5);
  add_cluster(particles, 5.0, 1.0, 0.0, 1, 5e-5);  // under the floor: missing
  const std::vector<cl::PlanCandidate> candidates = {
      candidate(2.1, 2.0, 0.1, 0.9),   // held by the leader
      candidate(6.0, 3.0, 0.0, 0.8),   // nobody there
      candidate(8.0, 4.2, 0.0, 0.7),   // held by the runner-up
      candidate(5.0, 1.0, 0.0, 0.6),   // a lone particle's
      candidate(2.0, 2.0, 3.14, 0.5),  // the leader's place, turned round: not held
  };
  EXPECT_EQ(xs(cl::missing_hypotheses(particles, candidates, {}, kHeight, 1e-4, 8)),
            (std::vector<double>{6.0, 5.0, 2.0}));
  // With a lower floor the lone particle holds its place; at most max_new, best first.
  EXPECT_EQ(xs(cl::missing_hypotheses(particles, candidates, {}, kHeight, 1e-5, 8)),
            (std::vector<double>{6.0, 2.0}));
  EXPECT_EQ(xs(cl::missing_hypotheses(particles, candidates, {}, kHeight, 1e-4, 1)),
            (std::vector<double>{6.0}));
}

TEST(MissingHypotheses, APlaceOnAnotherStoreyIsMissingAndOnePlaceIsAddedOnce) {
  cl::ParticleSet particles;
  add_cluster(particles, 2.0, 2.0, 0.0, 100, 1.0);
  const std::vector<cl::PlanCandidate> candidates = {
      candidate(2.0, 2.0, 0.0, 0.9, 3.0),   // above the leader, one storey up
      candidate(2.1, 2.0, 0.05, 0.8, 3.0),  // the same place, a few degrees apart
      candidate(2.0, 2.0, 0.0, 0.7),        // the leader's
  };
  EXPECT_EQ(cl::missing_hypotheses(particles, candidates, {}, kHeight, 1e-4, 8).size(), 1u);
  EXPECT_DOUBLE_EQ(cl::missing_hypotheses(particles, candidates, {}, kHeight, 1e-4, 8)[0].floor_z,
                   3.0);
}

TEST(AddHypotheses, AddsParticlesOfTheMeanWeightAndKeepsEveryHeldOne) {
  const conicloc::maps::PlaneMap map = ct::make_box_room();  // 10 m × 6 m
  const cl::FreeSpace free_space{map};
  const cl::MotionModel motion{cl::MotionModelConfig{}, free_space};
  cl::ParticleFilter filter(cl::ParticleFilterConfig{}, motion, free_space);
  add_cluster(filter.particles(), 2.0, 2.0, 0.0, 99, 1.0 - 1e-6);
  add_cluster(filter.particles(), 8.0, 4.0, 0.0, 1, 1e-6);  // the lightest: stays
  std::mt19937_64 rng(7);
  filter.add_hypotheses({candidate(6.0, 3.0, 1.0, 0.8), candidate(4.0, 1.0, -1.0, 0.7)}, 5, 0.1,
                        0.01, rng);
  const cl::ParticleSet& particles = filter.particles();
  ASSERT_EQ(particles.size(), 110u);
  // Each new particle entered at 1/100 of the old total: the total is now 1.1, normalised.
  double total = 0.0;
  for (const cl::Particle& p : particles) total += std::exp(p.log_weight);
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_NEAR(std::exp(particles[99].log_weight), 1e-6 / 1.1, 1e-15);
  for (std::size_t i = 100; i < 110; ++i) {
    const cl::Particle& p = particles[i];
    const double x = i < 105 ? 6.0 : 4.0;
    const double yaw = i < 105 ? 1.0 : -1.0;
    EXPECT_NEAR(std::exp(p.log_weight), 0.01 / 1.1, 1e-12);
    EXPECT_LT(std::hypot(p.state.x - x, p.state.y - (i < 105 ? 3.0 : 1.0)), 0.6);
    EXPECT_NEAR(p.state.yaw, yaw, 0.06);
    // On the room's floor (z = 0) at the mounting height.
    EXPECT_NEAR(p.state.z, motion.config().height_above_floor_m, 1e-9);
    EXPECT_GE(p.cell, 0);
  }
  // Nothing to add: the set stays as it was.
  filter.add_hypotheses({}, 5, 0.1, 0.01, rng);
  EXPECT_EQ(filter.particles().size(), 110u);
}
