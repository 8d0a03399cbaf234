// PlaneMap building blocks: coplanar merging, door openings, storeys; the shipped example building.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <limits>
#include <sstream>

#include "io/indoorgml.hpp"
#include "maps/surface_merge.hpp"
#include "tools/json_writer.hpp"

namespace {

using conicloc::maps::PlanarPolygon;
using conicloc::maps::Ring3;

PlanarPolygon wall_x(double x, double y0, double y1, bool facing_plus_x, int cell) {
  Ring3 ring = {{x, y0, 0}, {x, y1, 0}, {x, y1, 2.5}, {x, y0, 2.5}};  // normal +x
  if (!facing_plus_x) ring = {{x, y0, 0}, {x, y0, 2.5}, {x, y1, 2.5}, {x, y1, 0}};
  PlanarPolygon polygon;
  EXPECT_TRUE(conicloc::maps::make_planar_polygon(ring, {}, polygon));
  polygon.cell = cell;
  return polygon;
}

TEST(SurfaceMerge, ThinWallSeenFromBothSidesKeptOnceTwoSided) {
  std::vector<PlanarPolygon> polygons = {wall_x(4, 0, 3, false, 0), wall_x(4, 0, 3, true, 1)};
  conicloc::maps::MergeStats stats;
  const auto holder = conicloc::maps::merge_coplanar_faces(polygons, stats);
  ASSERT_EQ(polygons.size(), 1u);
  EXPECT_EQ(holder, (std::vector<int>{0, 0}));
  EXPECT_TRUE(polygons[0].two_sided);
  EXPECT_EQ(polygons[0].back_cell, 1);
  EXPECT_EQ(stats.faces_merged, 1);
}

TEST(SurfaceMerge, ShortWallInsideLongWallIsMergedPartialOverlapKept) {
  // A corridor wall 0..10 m covers a room wall 2..5 m; a wall 8..12 m only overlaps it.
  std::vector<PlanarPolygon> polygons = {wall_x(4, 0, 10, true, 0), wall_x(4, 2, 5, false, 1),
                                         wall_x(4, 8, 12, false, 2)};
  conicloc::maps::MergeStats stats;
  conicloc::maps::merge_coplanar_faces(polygons, stats);
  EXPECT_EQ(polygons.size(), 2u);
  EXPECT_EQ(stats.faces_merged, 1);
  EXPECT_EQ(stats.partial_overlaps, 1);
}

TEST(SurfaceMerge, ParallelWallsApartAndSameCellAreNotMerged) {
  std::vector<PlanarPolygon> polygons = {wall_x(4, 0, 3, false, 0), wall_x(4.1, 0, 3, true, 1),
                                         wall_x(6, 0, 3, true, 2), wall_x(6, 0, 3, true, 2)};
  conicloc::maps::MergeStats stats;
  conicloc::maps::merge_coplanar_faces(polygons, stats);
  EXPECT_EQ(polygons.size(), 4u);
}

TEST(SurfaceMerge, DoorBecomesHoleOrRemovesTheDoorFace) {
  PlanarPolygon door;
  ASSERT_TRUE(
      conicloc::maps::make_planar_polygon({{4, 1, 0}, {4, 2, 0}, {4, 2, 2}, {4, 1, 2}}, {}, door));
  std::vector<PlanarPolygon> polygons = {wall_x(4, 0, 3, false, 0), door};
  polygons[1].cell = 1;
  conicloc::maps::MergeStats stats;
  conicloc::maps::cut_door_openings(polygons, {door}, stats);
  ASSERT_EQ(polygons.size(), 1u);  // the shell face that was the door is gone
  EXPECT_EQ(stats.door_surfaces_removed, 1);
  EXPECT_EQ(stats.door_holes_cut, 1);
  EXPECT_NEAR(polygons[0].area, 7.5 - 2.0, 1e-12);
  EXPECT_EQ(polygons[0].cell, 0);
}

TEST(JsonWriter, NestingCommasEscapingNumbers) {
  std::ostringstream out;
  conicloc::tools::JsonWriter json(out);
  json.begin_object();
  json.key("s").value("a\"b\\c\n\x01");
  json.key("n").value(0.1);
  json.key("i").value(3);
  json.key("b").value(true);
  json.key("nan").value(std::nan(""));
  json.key("a").array({1.5, -2.0});
  json.key("o").begin_object().key("x").begin_array().end_array().end_object();
  json.end_object();
  EXPECT_EQ(out.str(),
            "{\"s\":\"a\\\"b\\\\c\\n\\u0001\",\"n\":0.1,\"i\":3,\"b\":true,\"nan\":null,"
            "\"a\":[1.5,-2],\"o\":{\"x\":[]}}");
}

TEST(JsonWriter, SubnormalNumbersReadBackExactly) {
  // A value pulled to 0 over many steps (a calibration's unseen plane) may be subnormal.
  for (const double tiny : {1e-310, -4e-320, std::numeric_limits<double>::denorm_min()}) {
    std::ostringstream out;
    conicloc::tools::JsonWriter json(out);
    json.begin_array().value(tiny).end_array();
    const std::string text = out.str();
    ASSERT_GT(text.size(), 2u);
    EXPECT_EQ(std::strtod(text.substr(1, text.size() - 2).c_str(), nullptr), tiny) << text;
  }
}

TEST(ExampleBuilding, LoadsWithItsCounts) {
  const std::string path = CONICLOC_EXAMPLE_MAP;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "example building absent: " << path;
  const auto loaded = conicloc::io::load_indoorgml(path);
  EXPECT_EQ(loaded.report.version, "1.0.3");
  EXPECT_EQ(loaded.report.cells_by_class.at("GeneralSpace"), 7);
  EXPECT_EQ(loaded.report.cells_by_class.at("TransitionSpace"), 3);
  EXPECT_EQ(loaded.report.polygons_read, 62);
  EXPECT_TRUE(loaded.report.polygons_dropped.empty());
  EXPECT_TRUE(loaded.report.warnings.empty());
  ASSERT_EQ(loaded.map.storeys.size(), 2u);
  EXPECT_NEAR(loaded.map.storeys[0].floor_z, 0.0, 1e-9);
  EXPECT_NEAR(loaded.map.storeys[1].floor_z, 3.2, 1e-9);
  EXPECT_TRUE(loaded.map.bounds.min().isApprox(Eigen::Vector3d(0, 0, 0), 1e-9) ||
              loaded.map.bounds.min().norm() < 1e-9);
  EXPECT_TRUE(loaded.map.bounds.max().isApprox(Eigen::Vector3d(18, 10, 6.2), 1e-9));
  EXPECT_EQ(loaded.map.navigation.nodes.size(), 10u);
  EXPECT_EQ(loaded.map.navigation.edges.size(), 10u);
  EXPECT_GT(loaded.report.two_sided_faces, 0);
  int sloped = 0;
  int through_door = 0;
  for (const auto& polygon : loaded.map.polygons) {
    sloped += polygon.kind == conicloc::maps::SurfaceKind::Slope ? 1 : 0;
    EXPECT_GE(polygon.storey, 0);
  }
  for (const auto& edge : loaded.map.navigation.edges) through_door += edge.through_door ? 1 : 0;
  EXPECT_GT(sloped, 0);  // the sloped roof of room D and the stair
  EXPECT_GT(through_door, 0);
}

}  // namespace
