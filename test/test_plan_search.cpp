// The floor-plan search of a global start (localizer/filter/plan_field.hpp, plan_search.hpp):
// the field and its max-pyramid against brute force, and known poses found from synthetic scans
// of the box room (own ray cast), the symmetric room's two poses both kept.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "localizer/conic/pose.hpp"
#include "localizer/filter/free_space.hpp"
#include "localizer/filter/motion_model.hpp"
#include "localizer/filter/particle_filter.hpp"
#include "localizer/filter/plan_field.hpp"
#include "localizer/filter/plan_search.hpp"
#include "maps/segment_distance.hpp"
#include "synthetic_room.hpp"

namespace cl = conicloc::localizer;
namespace cm = conicloc::maps;
namespace ct = conicloc::test;

namespace {

cm::SectionSegment segment(double ax, double ay, double bx, double by) {
  return {Eigen::Vector3d(ax, ay, 1.0), Eigen::Vector3d(bx, by, 1.0)};
}

/// The box room without its pillar: symmetric under a half turn about its centre (5, 3).
cm::PlaneMap symmetric_room() {
  cm::PlaneMap map = ct::make_box_room();
  map.polygons.resize(6);
  map.cells[0].polygons.resize(6);
  return map;
}

conicloc::sensor::Scan scan_at(const cm::PlaneMap& map, double x, double y, double yaw_rad) {
  std::mt19937_64 rng(4);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.4 * M_PI / 180.0;
  options.range_sigma_m = 0.02;
  return ct::make_scan(map, cl::make_pose(x, y, 1.2, yaw_rad), options, rng);
}

/// A hall 40 m × 30 m with a 2 m ceiling and two pillars that break its symmetry, one navigable
/// cell: from (18, 13), 0.7 m up, its walls stand 13–22 m off, the −3° ring meets the floor
/// 13.4 m off and the +3° ring the ceiling 24.8 m off.
cm::PlaneMap low_hall() {
  cm::PlaneMap map = ct::make_empty_room("hall", {40, 30, 2});
  ct::add_box(map, 0, {30.0, 20.0, 0.0}, {31.0, 21.0, 2.0}, false);
  ct::add_box(map, 0, {6.0, 24.0, 0.0}, {7.0, 25.0, 2.0}, false);
  return map;
}

bool near_pose(const cl::PlanCandidate& c, double x, double y, double yaw_rad, double xy_m,
               double yaw_tolerance_rad) {
  return std::hypot(c.x - x, c.y - y) <= xy_m &&
         std::abs(cl::angle_difference(c.yaw, yaw_rad)) <= yaw_tolerance_rad;
}

}  // namespace

TEST(PlanField, LevelZeroIsTheGaussianOfTheDistanceFromEachCellCentre) {
  const double resolution = 0.1, sigma = 0.1;
  const cl::PlanField field({segment(1.0, 1.0, 3.0, 1.0)},
                            Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(4, 2)),
                            resolution, sigma, 1);
  EXPECT_EQ(field.width(), 41);
  EXPECT_EQ(field.height(), 21);
  for (int j = 0; j < field.height(); ++j) {
    for (int i = 0; i < field.width(); ++i) {
      const Eigen::Vector2d centre = resolution * Eigen::Vector2d(i + 0.5, j + 0.5);
      const double d2 = cm::squared_distance_to_segment(centre, {1.0, 1.0}, {3.0, 1.0});
      const int expected =
          d2 > 9.0 * sigma * sigma
              ? 0
              : static_cast<int>(std::lround(255.0 * std::exp(-d2 / (2 * sigma * sigma))));
      ASSERT_EQ(field.at(0, i, j), expected) << i << ", " << j;
    }
  }
  EXPECT_EQ(field.at(0, -1, 10), 0);
  EXPECT_EQ(field.at(0, 41, 10), 0);
}

TEST(PlanField, EachLevelIsTheMaximumOfLevelZeroOverItsWindow) {
  // The walls reach the grid's edges, so windows starting before it overlap them.
  const cl::PlanField field({segment(0.3, 0.2, 2.7, 1.9), segment(1.0, 2.5, 1.1, 0.1)},
                            Eigen::AlignedBox2d(Eigen::Vector2d(0, 0), Eigen::Vector2d(3, 3)), 0.1,
                            0.08, 5);
  ASSERT_EQ(field.levels(), 5);
  for (int k = 1; k < field.levels(); ++k) {
    for (int j = -3; j < field.height(); j += 2) {
      for (int i = -3; i < field.width(); i += 3) {
        int brute = 0;
        for (int b = 0; b < (1 << k); ++b)
          for (int a = 0; a < (1 << k); ++a)
            brute = std::max<int>(brute, field.at(0, i + a, j + b));
        // Exact for a window starting in the grid; a bound for one starting before it.
        if (i >= 0 && j >= 0)
          ASSERT_EQ(field.at(k, i, j), brute) << "level " << k << " at " << i << ", " << j;
        else
          ASSERT_GE(field.at(k, i, j), brute) << "level " << k << " at " << i << ", " << j;
      }
    }
  }
}

TEST(PlanField, APaddedFieldIsTheFieldWithZeroCellsAroundIt) {
  // The walls cross the extent's edges: what lies outside it is not painted, and windows that
  // start in the padding hold exactly the cells of the extent they overlap.
  const std::vector<cm::SectionSegment> walls{segment(-0.5, 0.2, 2.7, 1.9),
                                              segment(1.0, 3.5, 1.1, 0.1)};
  const Eigen::AlignedBox2d extent(Eigen::Vector2d(0, 0), Eigen::Vector2d(3, 3));
  const int padding = 7;
  const cl::PlanField plain(walls, extent, 0.1, 0.08, 5);
  const cl::PlanField padded(walls, extent, 0.1, 0.08, 5, padding);
  ASSERT_EQ(padded.width(), plain.width() + 2 * padding);
  ASSERT_EQ(padded.height(), plain.height() + 2 * padding);
  EXPECT_TRUE(padded.origin().isApprox(plain.origin() - Eigen::Vector2d::Constant(0.7)));
  for (int k = 0; k < padded.levels(); ++k) {
    const std::uint8_t* cells = padded.cells(k);
    for (int j = 0; j < padded.height(); ++j) {
      for (int i = 0; i < padded.width(); ++i) {
        int brute = 0;
        for (int b = 0; b < (1 << k); ++b)
          for (int a = 0; a < (1 << k); ++a) {
            const int pi = i + a - padding, pj = j + b - padding;
            if (pi >= 0 && pj >= 0) brute = std::max<int>(brute, plain.at(0, pi, pj));
          }
        ASSERT_EQ(cells[j * padded.width() + i], brute)
            << "level " << k << " at " << i << ", " << j;
        ASSERT_EQ(padded.at(k, i, j), brute);
      }
    }
  }
}

TEST(PlanSearch, FindsTheTruePoseOfTheBoxRoomOverAllHeadings) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  const cl::PlanSearch search(map, free_space, 1.2, {});
  for (const auto& [x, y, yaw] : {std::tuple{3.0, 2.5, 0.5}, std::tuple{8.3, 4.4, -2.0}}) {
    const auto candidates = search.search(scan_at(map, x, y, yaw), {}, 2);
    ASSERT_FALSE(candidates.empty());
    // The best one within a cell and a heading step; all on the room's free floor.
    EXPECT_TRUE(near_pose(candidates.front(), x, y, yaw, 0.3, 1.5 * M_PI / 180.0))
        << candidates.front().x << ", " << candidates.front().y << ", " << candidates.front().yaw;
    EXPECT_GT(candidates.front().score, 0.6);
    for (const auto& c : candidates) {
      EXPECT_EQ(c.cell, 0);
      EXPECT_LE(c.score, candidates.front().score);
    }
  }
}

TEST(PlanSearch, SearchesOnlyAboutTheProposedHeadings) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  const cl::PlanSearch search(map, free_space, 1.2, {});
  const auto scan = scan_at(map, 3.0, 2.5, 0.5);
  const auto right = search.search(scan, {0.51}, 1);
  ASSERT_FALSE(right.empty());
  EXPECT_TRUE(near_pose(right.front(), 3.0, 2.5, 0.5, 0.3, 1.5 * M_PI / 180.0));
  const auto off = search.search(scan, {0.5 + M_PI / 2.0}, 1);
  ASSERT_FALSE(off.empty());
  // A proposal 90° off finds only poses at that heading (± the window, 2°, rounded up to whole
  // steps of ≤ 2° at the room's ranges), none of them the truth.
  for (const auto& c : off) {
    EXPECT_LE(std::abs(cl::angle_difference(c.yaw, 0.5 + M_PI / 2.0)), 4.0 * M_PI / 180.0);
    EXPECT_LT(c.score, right.front().score);
  }
}

TEST(PlanSearch, GivesTheSameCandidatesForAnyThreadCount) {
  const auto map = symmetric_room();
  const cl::FreeSpace free_space(map);
  const cl::PlanSearch search(map, free_space, 1.2, {});
  const auto scan = scan_at(map, 3.0, 2.2, 0.3);
  const auto one = search.search(scan, {}, 1);
  ASSERT_GE(one.size(), 2u);
  for (const int threads : {2, 5}) {
    const auto many = search.search(scan, {}, threads);
    ASSERT_EQ(many.size(), one.size()) << threads;
    for (std::size_t k = 0; k < one.size(); ++k) {
      EXPECT_EQ(many[k].x, one[k].x);
      EXPECT_EQ(many[k].y, one[k].y);
      EXPECT_EQ(many[k].yaw, one[k].yaw);
      EXPECT_EQ(many[k].score, one[k].score);
    }
  }
}

TEST(PlanSearch, GivesTheSameCandidatesHoweverManyNodesAreExpandedAtOnce) {
  // A corridor 100 m long seen from its middle: within the 30 m the search reaches, only its side
  // walls, which look the same from every place along it. The translations along it score
  // exactly alike, so the order of tied leaves decides which candidates are kept.
  const auto map = ct::make_empty_room("corridor", {100.0, 2.4, 3.0});
  const cl::FreeSpace free_space(map);
  const auto scan = scan_at(map, 50.0, 1.2, 0.0);
  const auto search_with = [&](std::size_t batch, int threads) {
    cl::PlanSearchConfig config;
    config.expand_batch = batch;
    return cl::PlanSearch(map, free_space, 1.2, config).search(scan, {0.0}, threads);
  };
  const auto one = search_with(1, 1);
  ASSERT_EQ(one.size(), cl::PlanSearchConfig{}.max_candidates);
  // Ties: candidates of one heading and score, kept in the order of their cells (x ascending).
  std::size_t ties = 0;
  for (std::size_t k = 1; k < one.size(); ++k) {
    if (one[k].score != one[k - 1].score || one[k].yaw != one[k - 1].yaw) continue;
    ++ties;
    EXPECT_GT(one[k].x, one[k - 1].x) << k;
  }
  EXPECT_GT(ties, 10u);
  for (const auto& [batch, threads] : {std::pair{std::size_t{3}, 1}, std::pair{std::size_t{64}, 2},
                                       std::pair{std::size_t{1000}, 2}}) {
    const auto many = search_with(batch, threads);
    ASSERT_EQ(many.size(), one.size()) << batch;
    for (std::size_t k = 0; k < one.size(); ++k) {
      EXPECT_EQ(many[k].x, one[k].x) << batch << " " << k;
      EXPECT_EQ(many[k].y, one[k].y) << batch << " " << k;
      EXPECT_EQ(many[k].yaw, one[k].yaw) << batch << " " << k;
      EXPECT_EQ(many[k].score, one[k].score) << batch << " " << k;
    }
  }
}

TEST(PlanSearch, RefusesAReachOrResolutionItCannotPadItsFieldsFor) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  for (const auto& [resolution, reach] :
       {std::pair{0.0, 30.0}, std::pair{-0.2, 30.0}, std::pair{0.2, -1.0},
        std::pair{0.2, std::numeric_limits<double>::infinity()},
        std::pair{std::numeric_limits<double>::quiet_NaN(), 30.0}}) {
    cl::PlanSearchConfig config;
    config.resolution_m = resolution;
    config.max_range_m = reach;
    EXPECT_THROW(cl::PlanSearch(map, free_space, 1.2, config), std::invalid_argument)
        << resolution << " " << reach;
  }
}

TEST(PlanSearch, KeepsBothPosesOfASymmetricRoom) {
  // Without the pillar the room looks the same from (x, y, ψ) and from its half turn
  // (10 − x, 6 − y, ψ + π): both must be candidates, with scores that differ by noise only.
  const auto map = symmetric_room();
  const cl::FreeSpace free_space(map);
  const cl::PlanSearch search(map, free_space, 1.2, {});
  const auto candidates = search.search(scan_at(map, 3.0, 2.2, 0.3), {}, 2);
  double truth = 0.0, mirror = 0.0;
  for (const auto& c : candidates) {
    if (near_pose(c, 3.0, 2.2, 0.3, 0.3, 1.5 * M_PI / 180.0)) truth = std::max(truth, c.score);
    if (near_pose(c, 7.0, 3.8, 0.3 + M_PI, 0.3, 1.5 * M_PI / 180.0))
      mirror = std::max(mirror, c.score);
  }
  EXPECT_GT(truth, 0.6);
  EXPECT_GT(mirror, 0.6);
  EXPECT_NEAR(truth, mirror, 0.05);
}

TEST(PlanSearch, MatchesTheNearHorizontalRingsThinned) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  cl::PlanSearchConfig config;
  const cl::PlanSearch search(map, free_space, 1.2, config);
  const auto scan = scan_at(map, 3.0, 2.5, 0.5);
  const auto points = search.search_points(scan);
  ASSERT_FALSE(points.empty());
  EXPECT_LE(points.size(), config.max_points);
  // From 1.2 m over the floor and 1.8 m under the ceiling, the VLP-16's rings within ±3.5° (±1°,
  // ±3°) reach the walls; their points lie on the room's walls or the pillar, in the sensor's
  // horizontal plane.
  const cl::Pose3 T_map_sensor = cl::make_pose(3.0, 2.5, 1.2, 0.5);
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector3d q = T_map_sensor * Eigen::Vector3d(p.x(), p.y(), 0.0);
    const double to_walls = std::min({q.x(), 10.0 - q.x(), q.y(), 6.0 - q.y()});
    const double to_pillar = std::max({7.0 - q.x(), q.x() - 8.0, 1.0 - q.y(), q.y() - 1.6});
    EXPECT_LT(std::min(std::abs(to_walls), std::abs(to_pillar)), 0.1) << q.transpose();
  }
}

TEST(PlanSearch, LeavesOutTheFloorAndCeilingAndReachesTheWallsOfAHall) {
  // A level sensor 0.7 m up in a low hall: the down-looking rings meet the floor and the
  // up-looking ones the ceiling within the search's reach. Those returns lie on no wall; every
  // point matched must lie on a wall or a pillar, and enough of them reach the far walls for
  // the true pose to be the best candidate. (Out to 15 m only, as before, the points were the
  // −3° ring's floor circle and the pillars: no pose fitted a quarter of them.)
  const auto map = low_hall();
  const cl::FreeSpace free_space(map);
  const cl::PlanSearchConfig config;
  const cl::PlanSearch search(map, free_space, 0.7, config);
  std::mt19937_64 rng(9);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * M_PI / 180.0;
  options.range_sigma_m = 0.02;
  const double x = 18.0, y = 13.0, yaw = 0.4;
  const auto scan = ct::make_scan(map, cl::make_pose(x, y, 0.7, yaw), options, rng);
  const auto points = search.search_points(scan);
  ASSERT_GE(points.size(), 200u);
  const cl::Pose3 T_map_sensor = cl::make_pose(x, y, 0.7, yaw);
  std::size_t beyond_15_m = 0;
  for (const Eigen::Vector2d& p : points) {
    const Eigen::Vector3d q = T_map_sensor * Eigen::Vector3d(p.x(), p.y(), 0.0);
    const double to_walls = std::min({q.x(), 40.0 - q.x(), q.y(), 30.0 - q.y()});
    const double to_pillars =
        std::min(std::max({30.0 - q.x(), q.x() - 31.0, 20.0 - q.y(), q.y() - 21.0}),
                 std::max({6.0 - q.x(), q.x() - 7.0, 24.0 - q.y(), q.y() - 25.0}));
    EXPECT_LT(std::min(std::abs(to_walls), std::abs(to_pillars)), 0.1) << q.transpose();
    if (p.norm() > 15.0) ++beyond_15_m;
  }
  EXPECT_GT(beyond_15_m, points.size() / 2);
  const auto candidates = search.search(scan, {}, 2);
  ASSERT_FALSE(candidates.empty());
  EXPECT_TRUE(near_pose(candidates.front(), x, y, yaw, 0.3, 1.5 * M_PI / 180.0))
      << candidates.front().x << ", " << candidates.front().y << ", " << candidates.front().yaw;
  EXPECT_GT(candidates.front().score, 0.6);
}

TEST(PlanSearch, AFewSmallLowCellsDoNotSetTheCeiling) {
  // Three navigable cells of a square metre each, 0.5 m high (door or stair cells as a map may
  // model them), beside the hall's 1,200 m²: the ceiling is the one over most of the floor, and
  // the hall's returns are matched as without them. Were the lowest ceiling taken, 0.5 m is
  // under the sensor and no return would be kept.
  auto map = low_hall();
  for (int k = 0; k < 3; ++k) {
    cm::Cell cell = map.cells[0];
    cell.id = "low" + std::to_string(k);
    const double x0 = 41.0 + 2.0 * k;
    cell.footprint = {{x0, 0}, {x0 + 1, 0}, {x0 + 1, 1}, {x0, 1}};
    cell.bounds = Eigen::AlignedBox3d(Eigen::Vector3d(x0, 0, 0), Eigen::Vector3d(x0 + 1, 1, 0.5));
    cell.ceiling_z = 0.5;
    cell.polygons.clear();
    map.cells.push_back(cell);
  }
  const auto hall = low_hall();
  const cl::FreeSpace free_space(map), hall_free_space(hall);
  const cl::PlanSearch search(map, free_space, 0.7, {});
  const cl::PlanSearch hall_search(hall, hall_free_space, 0.7, {});
  std::mt19937_64 rng(9);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * M_PI / 180.0;
  const auto scan = ct::make_scan(hall, cl::make_pose(18.0, 13.0, 0.7, 0.4), options, rng);
  const auto points = search.search_points(scan);
  ASSERT_GE(points.size(), 200u);
  EXPECT_EQ(points.size(), hall_search.search_points(scan).size());
}

TEST(PlanSearch, ASensorNearTheFloorKeepsItsLevelRings) {
  // A small robot's sensor 0.2 m up: a return of the +1° ring is 0.017·d above the sensor, so a
  // fixed 0.25 m clearance would take every one of them for the floor. The clearance is at most
  // half the way to the floor: the +1° ring alone still gives the room's walls.
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  const cl::PlanSearch search(map, free_space, 0.2, {});
  std::mt19937_64 rng(3);
  ct::SyntheticScanOptions options;
  options.azimuth_step_rad = 0.2 * M_PI / 180.0;
  auto scan = ct::make_scan(map, cl::make_pose(3.0, 2.5, 0.2, 0.5), options, rng);
  for (auto& ring : scan.rings)
    if (std::abs(ring.elevation_rad - M_PI / 180.0) > 1e-3) ring.returns.clear();
  const auto points = search.search_points(scan);
  EXPECT_GE(points.size(), 100u);
  const auto candidates = search.search(scan, {}, 2);
  ASSERT_FALSE(candidates.empty());
  EXPECT_TRUE(near_pose(candidates.front(), 3.0, 2.5, 0.5, 0.3, 1.5 * M_PI / 180.0));
}

TEST(ParticleFilter, DrawsTheGivenRangeOfParticlesAboutThePlanCandidates) {
  const auto map = ct::make_box_room();
  const cl::FreeSpace free_space(map);
  const cl::MotionModel motion(ct::noiseless_motion(1.2), free_space);
  cl::ParticleFilter filter({}, motion, free_space);
  std::mt19937_64 rng(2);
  filter.initialise_global(400, rng);
  const cl::ParticleSet before = filter.particles();
  cl::PlanCandidate a, b;
  a.x = 2.0, a.y = 2.0, a.yaw = 0.4, a.cell = 0;
  b.x = 5.0, b.y = 4.0, b.yaw = -1.0, b.cell = 0;
  filter.draw_about({a, b}, 100, 200, 0.1, 0.01, rng);
  const cl::ParticleSet& after = filter.particles();
  int near_a = 0, near_b = 0;
  for (std::size_t i = 0; i < after.size(); ++i) {
    const cl::PoseState& s = after[i].state;
    if (i < 100 || i >= 300) {
      EXPECT_EQ(s.x, before[i].state.x) << i;
      continue;
    }
    EXPECT_EQ(after[i].cell, 0);
    EXPECT_NEAR(s.z, 1.2, 1e-9);
    if (std::hypot(s.x - a.x, s.y - a.y) < 0.5 && std::abs(s.yaw - a.yaw) < 0.05) ++near_a;
    if (std::hypot(s.x - b.x, s.y - b.y) < 0.5 && std::abs(s.yaw - b.yaw) < 0.05) ++near_b;
  }
  EXPECT_EQ(near_a, 100);
  EXPECT_EQ(near_b, 100);
}
