#include <gtest/gtest.h>

#include <cmath>

#include "maps/planar_polygon.hpp"

namespace cm = conicloc::maps;
using Eigen::Vector3d;

TEST(PlanarPolygon, WallWithDoorHole) {
  // A 4 m × 3 m wall in the plane y = 2, ring runs clockwise in (x, z), so the normal is +y.
  const cm::Ring3 outer = {{0, 2, 0}, {0, 2, 3}, {4, 2, 3}, {4, 2, 0}};
  const cm::Ring3 door = {{1, 2, 0.01}, {2, 2, 0.01}, {2, 2, 2.0}, {1, 2, 2.0}};
  cm::PlanarPolygon polygon;
  ASSERT_TRUE(cm::make_planar_polygon(outer, {door}, polygon));
  EXPECT_NEAR(polygon.plane.normal.y(), 1.0, 1e-12);
  EXPECT_NEAR(polygon.plane.offset, -2.0, 1e-12);
  EXPECT_EQ(polygon.kind, cm::SurfaceKind::Wall);
  EXPECT_NEAR(polygon.area, 12.0 - 1.99, 1e-9);
  EXPECT_NEAR(polygon.flatness_m, 0.0, 1e-12);
  EXPECT_TRUE(polygon.contains_uv(polygon.frame.project(Vector3d(3, 2, 1))));
  EXPECT_FALSE(polygon.contains_uv(polygon.frame.project(Vector3d(1.5, 2, 1))));  // in the door
  EXPECT_FALSE(polygon.contains_uv(polygon.frame.project(Vector3d(5, 2, 1))));
  EXPECT_NEAR((polygon.centroid - Vector3d(2, 2, 1.5)).norm(), 0.0, 1e-12);
  EXPECT_GT(cm::signed_area(polygon.outer_uv), 0.0);
  EXPECT_LT(cm::signed_area(polygon.holes_uv[0]), 0.0);
}

TEST(PlanarPolygon, ClosedRingWithRepeatsEqualsOpenRing) {
  const cm::Ring3 open = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const cm::Ring3 messy = {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 0}};
  cm::PlanarPolygon a, b;
  ASSERT_TRUE(cm::make_planar_polygon(open, {}, a));
  ASSERT_TRUE(cm::make_planar_polygon(messy, {}, b));
  EXPECT_EQ(a.outer.size(), 4u);
  EXPECT_EQ(b.outer.size(), 4u);
  EXPECT_EQ(a.kind, cm::SurfaceKind::Floor);
  EXPECT_NEAR(a.area, b.area, 1e-15);
}

TEST(PlanarPolygon, DegenerateRingsAreRejected) {
  cm::PlanarPolygon polygon;
  EXPECT_FALSE(cm::make_planar_polygon({{0, 0, 0}, {1, 0, 0}, {0, 0, 0}}, {}, polygon));
  EXPECT_FALSE(cm::make_planar_polygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}}, {}, polygon));
  const double nan = std::nan("");
  EXPECT_FALSE(cm::make_planar_polygon({{0, 0, 0}, {1, 0, nan}, {1, 1, 0}}, {}, polygon));
}

TEST(PlanarPolygon, NonPlanarRingReportsFlatness) {
  const cm::Ring3 warped = {{0, 0, 0}, {1, 0, 0.01}, {1, 1, 0}, {0, 1, 0.01}};
  cm::PlanarPolygon polygon;
  ASSERT_TRUE(cm::make_planar_polygon(warped, {}, polygon));
  EXPECT_NEAR(polygon.flatness_m, 0.005, 1e-6);  // least squares splits the warp evenly
  for (const auto& p : polygon.outer) EXPECT_NEAR(polygon.plane.signed_distance(p), 0.0, 1e-12);
}

TEST(PlanarPolygon, TinyPolygonIsKept) {
  const cm::Ring3 tiny = {{0, 0, 0}, {1e-3, 0, 0}, {1e-3, 1e-3, 0}, {0, 1e-3, 0}};
  cm::PlanarPolygon polygon;
  ASSERT_TRUE(cm::make_planar_polygon(tiny, {}, polygon));
  EXPECT_NEAR(polygon.area, 1e-6, 1e-15);
}
