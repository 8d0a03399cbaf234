// Ear-clipping triangulation: areas, counts and coverage on convex, concave and holed polygons.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "io/indoorgml.hpp"
#include "maps/polygon_triangulation.hpp"
#include "test/shared_buildings.hpp"

namespace cm = conicloc::maps;

namespace {

constexpr double kPi = 3.14159265358979323846;

std::vector<Eigen::Vector2d> all_vertices(const cm::Ring2& outer,
                                          const std::vector<cm::Ring2>& holes) {
  std::vector<Eigen::Vector2d> v(outer.begin(), outer.end());
  for (const auto& h : holes) v.insert(v.end(), h.begin(), h.end());
  return v;
}

double triangle_area(const std::vector<Eigen::Vector2d>& v, const cm::Triangle& t) {
  const Eigen::Vector2d a = v[static_cast<std::size_t>(t[0])];
  const Eigen::Vector2d b = v[static_cast<std::size_t>(t[1])];
  const Eigen::Vector2d c = v[static_cast<std::size_t>(t[2])];
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

double polygon_area(const cm::Ring2& outer, const std::vector<cm::Ring2>& holes) {
  double area = std::abs(cm::signed_area(outer));
  for (const auto& h : holes) area -= std::abs(cm::signed_area(h));
  return area;
}

bool inside(const cm::Ring2& outer, const std::vector<cm::Ring2>& holes, const Eigen::Vector2d& p) {
  if (!cm::ring_contains(outer, p)) return false;
  for (const auto& h : holes) {
    if (cm::ring_contains(h, p)) return false;
  }
  return true;
}

// Checks the triangulation covers exactly the polygon: every triangle counter-clockwise with
// its centroid inside, and the areas summing to the polygon's area.
void expect_exact_cover(const cm::Ring2& outer, const std::vector<cm::Ring2>& holes,
                        const std::vector<cm::Triangle>& triangles) {
  const auto v = all_vertices(outer, holes);
  const double area = polygon_area(outer, holes);
  double sum = 0.0;
  for (const auto& t : triangles) {
    for (const int i : t) ASSERT_TRUE(i >= 0 && i < static_cast<int>(v.size()));
    const double a = triangle_area(v, t);
    EXPECT_GT(a, 0.0);
    sum += a;
    const Eigen::Vector2d centroid =
        (v[static_cast<std::size_t>(t[0])] + v[static_cast<std::size_t>(t[1])] +
         v[static_cast<std::size_t>(t[2])]) /
        3.0;
    EXPECT_TRUE(inside(outer, holes, centroid)) << centroid.transpose();
  }
  EXPECT_NEAR(sum, area, 1e-9 * std::max(1.0, area));
}

bool revisits_a_vertex(const cm::Ring2& ring) {
  for (std::size_t i = 0; i < ring.size(); ++i) {
    for (std::size_t j = i + 1; j < ring.size(); ++j) {
      if ((ring[i] - ring[j]).norm() < 1e-9) return true;
    }
  }
  return false;
}

cm::Ring2 star(std::mt19937& rng, const Eigen::Vector2d& center, double r_min, double r_max,
               int n) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  cm::Ring2 ring;
  for (int k = 0; k < n; ++k) {
    const double angle = 2 * kPi * (k + 0.9 * unit(rng)) / n;
    const double r = r_min + (r_max - r_min) * unit(rng);
    ring.push_back(center + r * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  return ring;
}

}  // namespace

TEST(Triangulation, SquareGivesTwoTriangles) {
  const cm::Ring2 square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const auto triangles = cm::triangulate(square, {});
  EXPECT_EQ(triangles.size(), 2u);
  expect_exact_cover(square, {}, triangles);
}

TEST(Triangulation, ClockwiseInputGivesCounterClockwiseTriangles) {
  const cm::Ring2 square{{0, 0}, {0, 2}, {2, 2}, {2, 0}};
  const auto triangles = cm::triangulate(square, {});
  EXPECT_EQ(triangles.size(), 2u);
  expect_exact_cover(square, {}, triangles);
}

TEST(Triangulation, RandomConvexPolygons) {
  std::mt19937 rng(1);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 20;
    const auto ring = star(rng, {0, 0}, 5.0, 5.0, n);  // points on a circle: convex
    const auto triangles = cm::triangulate(ring, {});
    EXPECT_EQ(triangles.size(), static_cast<std::size_t>(n - 2));
    expect_exact_cover(ring, {}, triangles);
  }
}

TEST(Triangulation, RandomConcavePolygons) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 3 + trial % 40;
    const auto ring = star(rng, {1, -2}, 0.5, 6.0, n);
    const auto triangles = cm::triangulate(ring, {});
    EXPECT_EQ(triangles.size(), static_cast<std::size_t>(n - 2)) << "trial " << trial;
    expect_exact_cover(ring, {}, triangles);
  }
}

TEST(Triangulation, RandomPolygonsWithHoles) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const double r_min = 4.0;
    const auto outer = star(rng, {0, 0}, r_min, 8.0, 5 + trial % 30);
    // Up to four disjoint holes, one per quadrant of the inner disc, some concave.
    std::vector<cm::Ring2> holes;
    const int n_holes = 1 + trial % 4;
    for (int h = 0; h < n_holes; ++h) {
      const double angle = kPi / 4 + h * kPi / 2;
      const Eigen::Vector2d c = 2.0 * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      holes.push_back(star(rng, c, 0.3, 1.2, 3 + static_cast<int>(unit(rng) * 8)));
    }
    const auto triangles = cm::triangulate(outer, holes);
    std::size_t n = outer.size() - 2;
    for (const auto& h : holes) n += h.size() + 2;  // each bridge adds two vertices
    EXPECT_EQ(triangles.size(), n) << "trial " << trial;
    expect_exact_cover(outer, holes, triangles);
  }
}

TEST(Triangulation, HolesAlignedWithEachOtherAndTheRay) {
  // Holes whose rightmost vertices lie on one horizontal line, and outer vertices on it too:
  // the bridge ray passes exactly through vertices.
  const cm::Ring2 outer{{0, 0}, {10, 0}, {10, 2}, {12, 2}, {12, 4}, {10, 4}, {10, 6}, {0, 6}};
  const std::vector<cm::Ring2> holes{{{1, 1}, {1, 3}, {2, 2}},
                                     {{4, 2}, {3, 1}, {3, 3}},
                                     {{6, 1}, {6, 3}, {8, 3}, {8, 2}, {7, 2}, {7, 1}}};
  const auto triangles = cm::triangulate(outer, holes);
  expect_exact_cover(outer, holes, triangles);
}

TEST(Triangulation, WallWithDoorNotchAndWindowHole) {
  // The shape of a wall in examples/example_building.gml: a door notch reaching the floor
  // (collinear floor vertices) and a window as a hole.
  const cm::Ring2 wall{{0, 0},   {2.5, 0}, {2.5, 2.1}, {3.4, 2.1}, {3.4, 0},
                       {4.5, 0}, {6, 0},   {6, 3},     {0, 3}};
  const std::vector<cm::Ring2> window{{{4.0, 0.9}, {4.0, 2.1}, {5.5, 2.1}, {5.5, 0.9}}};
  const auto triangles = cm::triangulate(wall, window);
  expect_exact_cover(wall, window, triangles);
  EXPECT_NEAR(polygon_area(wall, window), 18.0 - 0.9 * 2.1 - 1.5 * 1.2, 1e-12);
}

TEST(Triangulation, KeyholeRingWithABridgeBothWays) {
  // One ring: around a 1 x 1 window (clockwise), across to the 4 x 4 outline, around it
  // (counter-clockwise), back across: the window is a hole.
  const cm::Ring2 ring{{3, 3}, {3, 2}, {2, 2}, {2, 3}, {3, 3},
                       {4, 4}, {0, 4}, {0, 0}, {4, 0}, {4, 4}};
  const auto triangles = cm::triangulate(ring, {});
  const cm::Ring2 outline{{0, 0}, {4, 0}, {4, 4}, {0, 4}};
  const std::vector<cm::Ring2> window{{{2, 2}, {3, 2}, {3, 3}, {2, 3}}};
  double area = 0.0;
  for (const auto& t : triangles) {
    area += triangle_area(ring, t);
    const Eigen::Vector2d c =
        (ring[static_cast<std::size_t>(t[0])] + ring[static_cast<std::size_t>(t[1])] +
         ring[static_cast<std::size_t>(t[2])]) /
        3.0;
    EXPECT_TRUE(inside(outline, window, c)) << c.transpose();
  }
  EXPECT_NEAR(area, 15.0, 1e-12);
}

TEST(Triangulation, KeyholeRingJumpingLoopToLoop) {
  // As written in FJK-Haus: window loop, jump to a door loop, jump to the outline, jump back to
  // the window: the three jumps form a triangle that holds no material.
  const cm::Ring2 ring{{3, 3},   {3, 2}, {2, 2}, {2, 3}, {3, 3}, {1, 1}, {0.5, 1}, {0.5, 1.5},
                       {1, 1.5}, {1, 1}, {0, 4}, {0, 0}, {4, 0}, {4, 4}, {0, 4}};
  double area = 0.0;
  for (const auto& t : cm::triangulate(ring, {})) area += triangle_area(ring, t);
  EXPECT_NEAR(area, 16.0 - 1.0 - 0.25, 1e-12);
}

TEST(Triangulation, FigureEightRingKeepsBothLobes) {
  const cm::Ring2 ring{{0, 0}, {2, 0}, {2, 2}, {3, 2}, {3, 3}, {2, 3}, {2, 2}, {0, 2}};
  double area = 0.0;
  for (const auto& t : cm::triangulate(ring, {})) area += triangle_area(ring, t);
  EXPECT_NEAR(area, 4.0 + 1.0, 1e-12);
}

TEST(Triangulation, PlanarPolygonIndicesReferToOuterThenHoles) {
  cm::PlanarPolygon polygon;
  ASSERT_TRUE(cm::make_planar_polygon({{0, 0, 0}, {4, 0, 0}, {4, 0, 3}, {0, 0, 3}},
                                      {{{1, 0, 1}, {2, 0, 1}, {2, 0, 2}, {1, 0, 2}}}, polygon));
  const auto triangles = cm::triangulate(polygon);
  ASSERT_EQ(triangles.size(), 8u);
  std::vector<Eigen::Vector3d> v(polygon.outer.begin(), polygon.outer.end());
  v.insert(v.end(), polygon.holes[0].begin(), polygon.holes[0].end());
  double area = 0.0;
  for (const auto& t : triangles) {
    const Eigen::Vector3d n =
        (v[static_cast<std::size_t>(t[1])] - v[static_cast<std::size_t>(t[0])])
            .cross(v[static_cast<std::size_t>(t[2])] - v[static_cast<std::size_t>(t[0])]);
    EXPECT_GT(n.dot(polygon.plane.normal), 0.0);  // triangles face like the polygon
    area += 0.5 * n.norm();
  }
  EXPECT_NEAR(area, polygon.area, 1e-12);
}

TEST(Triangulation, DegenerateAndInvalidInputEndsWithoutCrashing) {
  EXPECT_TRUE(cm::triangulate(cm::Ring2{{0, 0}, {1, 1}}, {}).empty());
  EXPECT_TRUE(cm::triangulate(cm::Ring2{{0, 0}, {1, 1}, {2, 2}, {3, 3}}, {}).empty());
  const cm::Ring2 bow_tie{{0, 0}, {2, 2}, {2, 0}, {0, 2}};
  EXPECT_LE(cm::triangulate(bow_tie, {}).size(), 2u);
  // A hole outside the outer ring is left out.
  const cm::Ring2 square{{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const auto triangles = cm::triangulate(square, {{{5, 5}, {6, 5}, {6, 6}}});
  expect_exact_cover(square, {}, triangles);
}

// Real models: every polygon the loader keeps (holes, notches, slivers, many vertices)
// triangulates to its own area. Rings that revisit a vertex (keyhole rings) are checked by the
// tests above: their shoelace area counts the jumps between loops, which enclose no material.
TEST(Triangulation, EveryPolygonOfTheSharedModelsKeepsItsArea) {
  const auto models = conicloc::test::shared_indoorgml_models();
  if (models.empty())
    GTEST_SKIP() << "no shared data at " << conicloc::test::shared_indoorgml_dir();
  int polygons = 0;
  int keyholes = 0;
  for (const auto& path : models) {
    const auto map = conicloc::io::load_indoorgml(path.string()).map;
    for (const auto& p : map.polygons) {
      if (revisits_a_vertex(p.outer_uv)) {
        ++keyholes;
        continue;
      }
      std::vector<Eigen::Vector2d> v(p.outer_uv.begin(), p.outer_uv.end());
      for (const auto& h : p.holes_uv) v.insert(v.end(), h.begin(), h.end());
      double area = 0.0;
      for (const auto& t : cm::triangulate(p)) area += std::abs(triangle_area(v, t));
      EXPECT_NEAR(area, p.area, 1e-6 * std::max(1.0, p.area))
          << path.filename() << " " << p.source_id;
      ++polygons;
    }
  }
  EXPECT_GT(polygons, 1000);
  EXPECT_LT(keyholes, polygons / 20);
}
