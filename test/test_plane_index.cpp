// PlaneIndex and the exact polygon distances, against brute force on random polygons.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "maps/plane_index.hpp"

namespace cm = conicloc::maps;

namespace {

constexpr double kPi = 3.14159265358979323846;

// An orthonormal basis (e_u, e_v) of the plane with unit normal n.
std::pair<Eigen::Vector3d, Eigen::Vector3d> basis(const Eigen::Vector3d& n) {
  const Eigen::Vector3d helper =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e_u = n.cross(helper).normalized();
  return {e_u, n.cross(e_u)};
}

// A random star-shaped (often concave) polygon around `center`, in a random plane, radius up to
// `size_m`, sometimes with a hole inside its inner radius.
cm::PlanarPolygon random_polygon(std::mt19937& rng, const Eigen::Vector3d& center, double size_m) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss(0.0, 1.0);
  Eigen::Vector3d normal(gauss(rng), gauss(rng), gauss(rng));
  if (unit(rng) < 0.4) normal = Eigen::Vector3d(normal.x(), normal.y(), 0.0);  // walls
  if (unit(rng) < 0.2) normal = Eigen::Vector3d::UnitZ();                      // floors
  normal.normalize();
  const auto [e_u, e_v] = basis(normal);
  const int n_vertices = 3 + static_cast<int>(unit(rng) * 10);
  const double min_radius = size_m * (0.3 + 0.3 * unit(rng));
  cm::Ring3 outer;
  for (int k = 0; k < n_vertices; ++k) {
    const double angle = 2.0 * kPi * (k + 0.8 * unit(rng)) / n_vertices;
    const double r = min_radius + (size_m - min_radius) * unit(rng);
    outer.push_back(center + r * (std::cos(angle) * e_u + std::sin(angle) * e_v));
  }
  std::vector<cm::Ring3> holes;
  if (unit(rng) < 0.4) {  // a square hole well inside the inner radius
    const double h = 0.4 * min_radius;
    holes.push_back({center + h * (-e_u - e_v), center + h * (e_u - e_v), center + h * (e_u + e_v),
                     center + h * (-e_u + e_v)});
  }
  cm::PlanarPolygon polygon;
  EXPECT_TRUE(cm::make_planar_polygon(outer, holes, polygon));
  return polygon;
}

// A few hundred polygons in a 60 m x 40 m x 10 m building-sized volume; a few large "floors".
cm::PlaneMap random_map(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> x(0.0, 60.0), y(0.0, 40.0), z(0.0, 10.0);
  std::uniform_real_distribution<double> size(0.2, 4.0);
  cm::PlaneMap map;
  for (int i = 0; i < count; ++i) {
    const double s = i % 50 == 0 ? 25.0 : size(rng);
    map.polygons.push_back(random_polygon(rng, {x(rng), y(rng), z(rng)}, s));
  }
  return map;
}

std::vector<int> brute_force(const cm::PlaneMap& map, const Eigen::Vector3d& p, double range_m) {
  std::vector<int> out;
  for (std::size_t i = 0; i < map.polygons.size(); ++i) {
    if ((cm::closest_point(map.polygons[i], p) - p).norm() <= range_m) {
      out.push_back(static_cast<int>(i));
    }
  }
  return out;
}

std::vector<int> brute_force(const cm::PlaneMap& map, const Eigen::AlignedBox3d& box,
                             double range_m) {
  std::vector<int> out;
  for (std::size_t i = 0; i < map.polygons.size(); ++i) {
    if (cm::distance_to_box(map.polygons[i], box) <= range_m) out.push_back(static_cast<int>(i));
  }
  return out;
}

// 10 m x 10 m floor at z = 0 with a 2 m x 2 m hole at its centre.
cm::PlanarPolygon floor_with_hole() {
  cm::PlanarPolygon polygon;
  EXPECT_TRUE(cm::make_planar_polygon({{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}},
                                      {{{4, 4, 0}, {6, 4, 0}, {6, 6, 0}, {4, 6, 0}}}, polygon));
  return polygon;
}

}  // namespace

TEST(ClosestPoint, InsideProjectsOntoThePlane) {
  const auto polygon = floor_with_hole();
  const Eigen::Vector3d c = cm::closest_point(polygon, {2, 3, 1.5});
  EXPECT_NEAR((c - Eigen::Vector3d(2, 3, 0)).norm(), 0.0, 1e-12);
}

TEST(ClosestPoint, OverTheHoleLandsOnTheHoleEdge) {
  const auto polygon = floor_with_hole();
  const Eigen::Vector3d c = cm::closest_point(polygon, {5, 4.5, 2});
  EXPECT_NEAR((c - Eigen::Vector3d(5, 4, 0)).norm(), 0.0, 1e-12);
}

TEST(ClosestPoint, OutsideLandsOnTheOuterEdgeOrCorner) {
  const auto polygon = floor_with_hole();
  EXPECT_NEAR((cm::closest_point(polygon, {-3, 5, 4}) - Eigen::Vector3d(0, 5, 0)).norm(), 0.0,
              1e-12);
  EXPECT_NEAR((cm::closest_point(polygon, {12, 13, -1}) - Eigen::Vector3d(10, 10, 0)).norm(), 0.0,
              1e-12);
}

TEST(ClosestPoint, NoSampledPolygonPointIsCloser) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const auto polygon = random_polygon(rng, Eigen::Vector3d::Zero(), 3.0);
    const Eigen::Vector3d p(8 * unit(rng) - 4, 8 * unit(rng) - 4, 8 * unit(rng) - 4);
    const double d = (cm::closest_point(polygon, p) - p).norm();
    EXPECT_LE(std::abs(polygon.plane.signed_distance(cm::closest_point(polygon, p))), 1e-9);
    // Sample the polygon on a uv grid: nothing closer, and something nearly as close.
    double sampled = std::numeric_limits<double>::infinity();
    const double step = 0.02;
    for (double u = -3; u <= 3; u += step) {
      for (double v = -3; v <= 3; v += step) {
        const Eigen::Vector2d uv(u, v);
        if (!polygon.contains_uv(uv)) continue;
        sampled = std::min(sampled, (polygon.frame.lift(uv) - p).norm());
      }
    }
    EXPECT_LE(d, sampled + 1e-12);
    EXPECT_GE(d, sampled - step * std::sqrt(2.0));
  }
}

TEST(DistanceToBox, DegenerateBoxIsThePointDistance) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-5.0, 5.0);
  for (int trial = 0; trial < 200; ++trial) {
    const auto polygon = random_polygon(rng, Eigen::Vector3d::Zero(), 3.0);
    const Eigen::Vector3d p(unit(rng), unit(rng), unit(rng));
    EXPECT_NEAR(cm::distance_to_box(polygon, Eigen::AlignedBox3d(p, p)),
                (cm::closest_point(polygon, p) - p).norm(), 1e-9);
  }
}

TEST(DistanceToBox, KnownCases) {
  const auto polygon = floor_with_hole();
  // Above the floor: the box bottom height.
  EXPECT_NEAR(cm::distance_to_box(polygon, {Eigen::Vector3d(1, 1, 2), Eigen::Vector3d(2, 2, 3)}),
              2.0, 1e-12);
  // Cut by the floor plane inside the hole only: nearest hole edge.
  EXPECT_NEAR(
      cm::distance_to_box(polygon, {Eigen::Vector3d(4.5, 4.5, -1), Eigen::Vector3d(5.5, 5.5, 1)}),
      0.5, 1e-12);
  // Cut by the plane and overlapping the floor: touching.
  EXPECT_EQ(cm::distance_to_box(polygon, {Eigen::Vector3d(3, 3, -1), Eigen::Vector3d(5, 5, 1)}),
            0.0);
  // Beside the floor, diagonally off a corner and above it.
  EXPECT_NEAR(
      cm::distance_to_box(polygon, {Eigen::Vector3d(13, 14, 2), Eigen::Vector3d(15, 15, 5)}),
      std::sqrt(9.0 + 16.0 + 4.0), 1e-12);
  EXPECT_TRUE(std::isinf(cm::distance_to_box(polygon, Eigen::AlignedBox3d())));
}

TEST(DistanceToBox, MatchesDenseSamplingOfTheBox) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const auto polygon = random_polygon(rng, Eigen::Vector3d::Zero(), 3.0);
    const Eigen::Vector3d corner(8 * unit(rng) - 5, 8 * unit(rng) - 5, 8 * unit(rng) - 5);
    const Eigen::Vector3d size(3 * unit(rng), 3 * unit(rng), 3 * unit(rng));
    const Eigen::AlignedBox3d box(corner, corner + size);
    const double exact = cm::distance_to_box(polygon, box);
    // The distance to the polygon is 1-Lipschitz, so the true minimum over the box is within
    // half a sample-cell diagonal of the sampled minimum.
    const int n = 16;
    double sampled = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i) {
      for (int j = 0; j <= n; ++j) {
        for (int k = 0; k <= n; ++k) {
          const Eigen::Vector3d p =
              corner + Eigen::Vector3d(i * size.x(), j * size.y(), k * size.z()) / n;
          sampled = std::min(sampled, (cm::closest_point(polygon, p) - p).norm());
        }
      }
    }
    EXPECT_LE(exact, sampled + 1e-9) << "trial " << trial;
    EXPECT_GE(exact, sampled - 0.5 * size.norm() / n - 1e-9) << "trial " << trial;
  }
}

TEST(PlaneIndex, PointQueriesMatchBruteForce) {
  std::mt19937 rng(42);
  const auto map = random_map(rng, 300);
  const cm::PlaneIndex index(map);
  std::uniform_real_distribution<double> x(-10.0, 70.0), y(-10.0, 50.0), z(-5.0, 15.0);
  std::uniform_real_distribution<double> range(0.0, 12.0);
  std::size_t total = 0;
  for (int q = 0; q < 3000; ++q) {
    const Eigen::Vector3d p(x(rng), y(rng), z(rng));
    const double r = range(rng);
    const auto expected = brute_force(map, p, r);
    total += expected.size();
    ASSERT_EQ(index.within(p, r), expected) << "query " << q;
  }
  EXPECT_GT(total, 3000u);  // the queries do find polygons
}

TEST(PlaneIndex, BoxQueriesMatchBruteForce) {
  std::mt19937 rng(43);
  const auto map = random_map(rng, 300);
  const cm::PlaneIndex index(map);
  std::uniform_real_distribution<double> x(-10.0, 70.0), y(-10.0, 50.0), z(-5.0, 15.0);
  std::uniform_real_distribution<double> extent(0.0, 6.0), range(0.0, 8.0);
  for (int q = 0; q < 1000; ++q) {
    const Eigen::Vector3d corner(x(rng), y(rng), z(rng));
    const Eigen::AlignedBox3d box(
        corner, corner + Eigen::Vector3d(extent(rng), extent(rng), 0.3 * extent(rng)));
    const double r = range(rng);
    ASSERT_EQ(index.within(box, r), brute_force(map, box, r)) << "query " << q;
  }
}

// A range that holds the whole map's box needs no search; around that range (the farthest
// corner of the map's box, where the shortcut starts) the answers still match brute force.
TEST(PlaneIndex, RangesAroundTheWholeMapMatchBruteForce) {
  std::mt19937 rng(44);
  auto map = random_map(rng, 300);
  // A small triangle at each corner of a box around the map: the map's farthest points are the
  // corners of its box.
  const Eigen::AlignedBox3d extent(Eigen::Vector3d(-30.0, -30.0, -30.0),
                                   Eigen::Vector3d(90.0, 70.0, 40.0));
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner = extent.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c));
    const Eigen::Vector3d in = (extent.center() - corner).cwiseSign() * 0.3;
    cm::PlanarPolygon triangle;
    ASSERT_TRUE(cm::make_planar_polygon(
        {corner, corner + Eigen::Vector3d(in.x(), 0, 0), corner + Eigen::Vector3d(0, in.y(), 0)},
        {}, triangle));
    map.polygons.push_back(triangle);
  }
  const cm::PlaneIndex index(map);
  std::uniform_real_distribution<double> x(-10.0, 70.0), y(-10.0, 50.0), z(-5.0, 15.0);
  std::uniform_real_distribution<double> scale(0.9, 1.1), size(0.0, 6.0);
  std::size_t whole = 0;
  for (int q = 0; q < 400; ++q) {
    const Eigen::Vector3d p(x(rng), y(rng), z(rng));
    double farthest = 0.0;
    for (int c = 0; c < 8; ++c) {
      farthest = std::max(
          farthest, (extent.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)) - p).norm());
    }
    const double r = scale(rng) * farthest;
    const auto expected = brute_force(map, p, r);
    whole += expected.size() == map.polygons.size() ? 1 : 0;
    ASSERT_EQ(index.within(p, r), expected) << "query " << q;
    const Eigen::AlignedBox3d box(p, p + Eigen::Vector3d(size(rng), size(rng), size(rng)));
    ASSERT_EQ(index.within(box, r), brute_force(map, box, r)) << "box query " << q;
  }
  EXPECT_GT(whole, 100U);  // the shortcut's side of the range is tested
}

TEST(PlaneIndex, RangeOnTheBoundaryIsIncluded) {
  cm::PlaneMap map;
  map.polygons.push_back(floor_with_hole());
  const cm::PlaneIndex index(map);
  EXPECT_EQ(index.within(Eigen::Vector3d(2, 2, 3), 3.0), std::vector<int>{0});
  EXPECT_TRUE(index.within(Eigen::Vector3d(2, 2, 3), 2.999).empty());
  EXPECT_TRUE(index.within(Eigen::Vector3d(5, 5, 0.5), 0.9).empty());  // over the hole
  EXPECT_EQ(index.within(Eigen::Vector3d(5, 5, 0), 1.0), std::vector<int>{0});
}

TEST(PlaneIndex, EmptyMapAndInvalidQueries) {
  const cm::PlaneMap empty;
  const cm::PlaneIndex empty_index(empty);
  EXPECT_TRUE(empty_index.within(Eigen::Vector3d::Zero(), 100.0).empty());
  EXPECT_TRUE(empty_index.within(Eigen::AlignedBox3d(Eigen::Vector3d::Zero()), 100.0).empty());

  cm::PlaneMap map;
  map.polygons.push_back(floor_with_hole());
  const cm::PlaneIndex index(map);
  EXPECT_TRUE(index.within(Eigen::Vector3d(1, 1, 0), -1.0).empty());
  EXPECT_TRUE(index.within(Eigen::Vector3d(NAN, 1, 0), 5.0).empty());
  EXPECT_TRUE(index.within(Eigen::AlignedBox3d(), 5.0).empty());
}

TEST(PlaneIndex, MovedIndexStillAnswers) {
  std::mt19937 rng(5);
  const auto map = random_map(rng, 60);
  cm::PlaneIndex first(map);
  const cm::PlaneIndex moved(std::move(first));
  const Eigen::Vector3d p(30, 20, 5);
  EXPECT_EQ(moved.within(p, 15.0), brute_force(map, p, 15.0));
}
