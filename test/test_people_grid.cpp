// The grid of people's walks (sim/people_grid.hpp): every walk within the distance visited, each
// once, and most of a building's people not visited by a query near one point.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "sim/people_grid.hpp"

namespace conicloc::sim {
namespace {

TEST(PeopleGrid, VisitsEveryWalkWithinTheDistanceOnce) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  // 300 walks in a 120 m × 60 m building: most a few metres long, some across it.
  std::vector<Eigen::AlignedBox2d> walks;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector2d from(120 * u(rng), 60 * u(rng));
    const double length = i % 30 == 0 ? 80.0 : 6.0;
    const Eigen::Vector2d to =
        from + length * Eigen::Vector2d(u(rng) - 0.5, u(rng) - 0.5).normalized();
    walks.emplace_back(from.cwiseMin(to).array() - 0.25, from.cwiseMax(to).array() + 0.25);
  }
  const PeopleGrid grid(walks);
  long visited_total = 0;
  const int queries = 2000;
  for (int q = 0; q < queries; ++q) {
    // Points in and around the building (up to 50 m outside), distances from 0 to 150 m.
    const Eigen::Vector2d point(-50 + 220 * u(rng), -50 + 160 * u(rng));
    const double distance = q % 10 == 0 ? 150 * u(rng) : 8 * u(rng);
    std::vector<int> visits(walks.size(), 0);
    grid.for_each_near(point, distance, [&](std::size_t i) { ++visits[i]; });
    for (std::size_t i = 0; i < walks.size(); ++i) {
      ASSERT_LE(visits[i], 1) << q << " " << i;
      if (walks[i].squaredExteriorDistance(point) <= distance * distance) {
        ASSERT_EQ(visits[i], 1) << "query " << q << " missed walk " << i;
      }
      visited_total += visits[i];
    }
  }
  // A query a few metres wide visits a few of the 300, not all of them.
  EXPECT_LT(visited_total, queries * 300 / 5);
  EXPECT_GT(visited_total, 0);
}

TEST(PeopleGrid, NoPeopleNoVisits) {
  const PeopleGrid grid(std::vector<Eigen::AlignedBox2d>{});
  int visits = 0;
  grid.for_each_near({0, 0}, 1e6, [&](std::size_t) { ++visits; });
  EXPECT_EQ(visits, 0);
}

TEST(PeopleGrid, APointWalkAndAHugeBuilding) {
  // A person standing still (a zero box), and walks 50 km apart (a grid of coarser cells): each
  // is found, alone.
  const std::vector<Eigen::AlignedBox2d> walks = {
      Eigen::AlignedBox2d(Eigen::Vector2d(1, 1), Eigen::Vector2d(1, 1)),
      Eigen::AlignedBox2d(Eigen::Vector2d(50000, 30000), Eigen::Vector2d(50001, 30002))};
  const PeopleGrid grid(walks);
  for (std::size_t i = 0; i < walks.size(); ++i) {
    std::vector<std::size_t> found;
    grid.for_each_near(walks[i].center(), 0.1, [&](std::size_t j) { found.push_back(j); });
    ASSERT_EQ(found.size(), 1u) << i;
    EXPECT_EQ(found.front(), i);
  }
}

}  // namespace
}  // namespace conicloc::sim
