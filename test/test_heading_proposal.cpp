// The headings a global start and a recovery draw: the map's wall directions, the scan's, and the
// yaws that align one with the other (localizer/filter/heading_proposal.hpp).

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "localizer/conic/pose.hpp"
#include "localizer/filter/heading_proposal.hpp"
#include "localizer/filter/particle_filter.hpp"
#include "synthetic_room.hpp"

namespace conicloc::localizer {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// Angle between two directions in [0, π) (mod π).
double direction_error(double a, double b) {
  const double d = std::fmod(std::abs(a - b), M_PI);
  return std::min(d, M_PI - d);
}

/// Distance of `yaw` from the nearest of `headings` (mod 2π).
double nearest_heading_error(const std::vector<double>& headings, double yaw) {
  double best = M_PI;
  for (const double h : headings) best = std::min(best, std::abs(angle_difference(h, yaw)));
  return best;
}

TEST(MapWallDirections, ManhattanRoomHasTwo) {
  const maps::PlaneMap map = test::make_box_room();
  const std::vector<double> directions = map_wall_directions(map);
  ASSERT_EQ(directions.size(), 2u);
  // Strongest first: the two 10 m walls (normals ±y) outweigh the two 6 m ones (±x).
  EXPECT_LT(direction_error(directions[0], M_PI / 2.0), 0.5 * kDeg);
  EXPECT_LT(direction_error(directions[1], 0.0), 0.5 * kDeg);
}

TEST(MapWallDirections, NonManhattanWallAddsItsDirection) {
  maps::PlaneMap map = test::make_box_room();
  // An 8 m wall at 45° across the room (its normal at 135°).
  const Eigen::Vector3d a(1, 0.5, 0), b(6.66, 6.16, 0);
  test::add_quad(map, 0, a, b, b + Eigen::Vector3d(0, 0, 3), a + Eigen::Vector3d(0, 0, 3));
  const std::vector<double> directions = map_wall_directions(map);
  ASSERT_EQ(directions.size(), 3u);
  EXPECT_LT(nearest_heading_error(directions, 135.0 * kDeg), 0.5 * kDeg);
}

TEST(MapWallDirections, FloorsAndCeilingsDoNotCount) {
  maps::PlaneMap map = test::make_box_room();
  std::erase_if(map.polygons,
                [](const maps::PlanarPolygon& p) { return p.kind == maps::SurfaceKind::Wall; });
  EXPECT_TRUE(map_wall_directions(map).empty());
}

TEST(HeadingProposal, ProposesTheTrueYawFromOneScan) {
  const maps::PlaneMap map = test::make_box_room();
  const std::vector<double> directions = map_wall_directions(map);
  std::mt19937_64 rng(3);
  test::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * kDeg;
  options.range_sigma_m = 0.03;  // a VLP-16's range noise
  for (const double yaw_deg : {0.0, 17.0, -63.0, 151.0}) {
    const Pose3 truth = make_pose(3.0, 2.5, 1.0, yaw_deg * kDeg);
    const sensor::Scan scan = test::make_scan(map, truth, options, rng);
    const HeadingProposal proposal = HeadingProposal::from_scan(directions, scan);
    // Two map directions, each with its reverse.
    ASSERT_EQ(proposal.headings().size(), 4u) << yaw_deg;
    EXPECT_LT(nearest_heading_error(proposal.headings(), yaw_of(truth)), 1.0 * kDeg) << yaw_deg;
  }
}

TEST(HeadingProposal, NothingFromAScanWithoutWalls) {
  // Every ring at a constant range: a sensor inside a cylinder shows no wall direction.
  sensor::Scan scan;
  scan.rings.resize(16);
  for (std::size_t r = 0; r < scan.rings.size(); ++r) {
    scan.rings[r].elevation_rad = (-15.0 + 2.0 * static_cast<double>(r)) * kDeg;
    for (int a = 0; a < 1800; ++a) {
      sensor::Return ret;
      ret.azimuth_rad = a * 0.2 * kDeg;
      ret.range_m = 5.0;
      scan.rings[r].returns.push_back(ret);
    }
  }
  EXPECT_FALSE(scan_wall_direction(scan).has_value());
  const HeadingProposal proposal = HeadingProposal::from_scan({0.0, M_PI / 2.0}, scan);
  EXPECT_TRUE(proposal.headings().empty());
}

TEST(HeadingProposal, DrawsMixUniformAndProposedHeadings) {
  std::mt19937_64 rng(5);
  const double sigma = 2.0 * kDeg;
  const HeadingProposal focused({0.3, -2.0}, sigma, 0.0);
  for (int i = 0; i < 2000; ++i) {
    EXPECT_LT(nearest_heading_error(focused.headings(), focused.draw(rng)), 5.0 * sigma);
  }
  // Half uniform: about half the draws fall farther than 5σ from both headings (which cover
  // 4 × 5σ of the 2π circle, ~11 %).
  const HeadingProposal mixed({0.3, -2.0}, sigma, 0.5);
  int far = 0;
  for (int i = 0; i < 4000; ++i) {
    const double yaw = mixed.draw(rng);
    ASSERT_GE(yaw, -M_PI);
    ASSERT_LE(yaw, M_PI);
    if (nearest_heading_error(mixed.headings(), yaw) > 5.0 * sigma) ++far;
  }
  EXPECT_NEAR(far / 4000.0, 0.5 * (1.0 - 20.0 * sigma / (2.0 * M_PI)), 0.03);
  // Without headings every draw is uniform, whatever fraction was asked for.
  const HeadingProposal none({}, sigma, 0.0);
  double sum_cos = 0.0;
  for (int i = 0; i < 4000; ++i) sum_cos += std::cos(none.draw(rng));
  EXPECT_NEAR(sum_cos / 4000.0, 0.0, 0.05);
}

TEST(HeadingProposal, SpreadDrawsCoverTheMixture) {
  std::mt19937_64 rng(9);
  // Uniform: four headings a quarter turn apart, each slot uniform over the whole turn.
  double slot_cos[4] = {0, 0, 0, 0}, slot_sin[4] = {0, 0, 0, 0};
  for (int g = 0; g < 1000; ++g) {
    const std::vector<double> yaws = HeadingProposal().draw_spread(4, rng);
    ASSERT_EQ(yaws.size(), 4u);
    for (int j = 0; j < 4; ++j) {
      ASSERT_GE(yaws[j], -M_PI);
      ASSERT_LE(yaws[j], M_PI);
      EXPECT_NEAR(std::abs(angle_difference(yaws[j], yaws[0] + j * M_PI / 2.0)), 0.0, 1e-12);
      slot_cos[j] += std::cos(yaws[j]) / 1000.0;
      slot_sin[j] += std::sin(yaws[j]) / 1000.0;
    }
  }
  for (int j = 0; j < 4; ++j) {  // σ of each mean: 0.022
    EXPECT_NEAR(slot_cos[j], 0.0, 0.08) << j;
    EXPECT_NEAR(slot_sin[j], 0.0, 0.08) << j;
  }
  // A Manhattan scan's four proposed headings, half the groups uniform: each group of four is
  // either a uniform star (noise-free quarter turns) or the four proposed headings, one each.
  const double sigma = 1.0 * kDeg;
  const std::vector<double> proposed = {0.1, 0.1 + M_PI, 0.1 + M_PI / 2.0, 0.1 - M_PI / 2.0};
  const HeadingProposal manhattan(proposed, sigma, 0.5);
  int proposed_groups = 0, far_stars = 0;
  for (int g = 0; g < 1000; ++g) {
    const std::vector<double> yaws = manhattan.draw_spread(4, rng);
    ASSERT_EQ(yaws.size(), 4u);
    bool quarter_turns = true;
    for (int j = 1; j < 4; ++j) {
      quarter_turns &= std::abs(angle_difference(yaws[j], yaws[0] + j * M_PI / 2.0)) < 1e-12;
    }
    if (quarter_turns) {
      // A star's headings are all near the proposed ones (also a quarter turn apart) or none.
      far_stars += nearest_heading_error(proposed, yaws[0]) > 5.0 * sigma ? 1 : 0;
      continue;
    }
    ++proposed_groups;
    std::set<std::size_t> nearest;
    for (const double yaw : yaws) {
      EXPECT_LT(nearest_heading_error(proposed, yaw), 5.0 * sigma);
      std::size_t k = 0;
      for (std::size_t h = 1; h < proposed.size(); ++h) {
        if (std::abs(angle_difference(proposed[h], yaw)) <
            std::abs(angle_difference(proposed[k], yaw)))
          k = h;
      }
      nearest.insert(k);
    }
    EXPECT_EQ(nearest.size(), 4u);
  }
  EXPECT_NEAR(proposed_groups / 1000.0, 0.5, 0.05);  // σ 0.016
  // The stars' offsets are uniform: far from the proposed headings but for 4 × 10σ of the turn.
  EXPECT_NEAR(far_stars / static_cast<double>(1000 - proposed_groups),
              1.0 - 40.0 * sigma / (2.0 * M_PI), 0.05);  // σ 0.014
  // Two proposed headings for four siblings: the two, and a uniform star of two, not twins.
  const HeadingProposal corridor({0.4, 0.4 + M_PI}, sigma, 0.0);
  int star_near_proposed = 0;
  for (int g = 0; g < 200; ++g) {
    const std::vector<double> yaws = corridor.draw_spread(4, rng);
    EXPECT_LT(nearest_heading_error(corridor.headings(), yaws[0]), 5.0 * sigma);
    EXPECT_LT(nearest_heading_error(corridor.headings(), yaws[1]), 5.0 * sigma);
    EXPECT_GT(std::abs(angle_difference(yaws[0], yaws[1])), M_PI - 10.0 * sigma);
    EXPECT_NEAR(std::abs(angle_difference(yaws[2], yaws[3])), M_PI, 1e-12);
    star_near_proposed += nearest_heading_error(corridor.headings(), yaws[2]) < 5.0 * sigma;
  }
  EXPECT_LT(star_near_proposed, 25);  // 10σ of π: 6 % of 200 by chance
  // One alone is a plain draw of the mixture; none is none.
  EXPECT_LT(nearest_heading_error({0.7}, HeadingProposal({0.7}, sigma, 0.0).draw_spread(1, rng)[0]),
            5.0 * sigma);
  EXPECT_TRUE(manhattan.draw_spread(0, rng).empty());
}

TEST(HeadingProposal, RestartDrawsItsGlobalParticlesFromIt) {
  const maps::PlaneMap map = test::make_box_room();
  const FreeSpace free_space(map);
  const MotionModel motion(test::noiseless_motion(1.0), free_space);
  ParticleFilter filter({}, motion, free_space);
  std::mt19937_64 rng(7);
  filter.initialise_global(100, rng);
  RestartMix mix;
  mix.headings = HeadingProposal({1.0}, 1.0 * kDeg, 0.0);
  filter.restart(500, mix, rng);
  ASSERT_EQ(filter.particles().size(), 500u);
  for (const Particle& p : filter.particles()) EXPECT_NEAR(p.state.yaw, 1.0, 5.0 * kDeg);
  // A global start's first scan redraws them all.
  filter.draw_headings(HeadingProposal({-2.5}, 1.0 * kDeg, 0.0), 1, rng);
  for (const Particle& p : filter.particles()) EXPECT_NEAR(p.state.yaw, -2.5, 5.0 * kDeg);
}

}  // namespace
}  // namespace conicloc::localizer
