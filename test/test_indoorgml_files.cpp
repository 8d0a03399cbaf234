// IndoorGML loading: the shared real models, the version forms and geometry cases of test/data.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numeric>

#include "io/indoorgml.hpp"

namespace {

using conicloc::io::load_indoorgml;
using conicloc::io::LoadedMap;
using conicloc::io::MapLoadOptions;

std::string shared_file(const std::string& name) {
  return std::string(CONICLOC_SHARED_DATA) + "/indoorgml/" + name;
}
std::string test_file(const std::string& name) {
  return std::string(CONICLOC_TEST_DATA) + "/indoorgml/" + name;
}

int total(const std::map<std::string, int>& counts) {
  return std::accumulate(counts.begin(), counts.end(), 0,
                         [](int sum, const auto& entry) { return sum + entry.second; });
}

// Every surface faces into its cell: a point a little in front of it along the normal lies
// within the cell's bounds (boxes here are convex).
void expect_normals_into_cells(const LoadedMap& loaded) {
  for (const auto& polygon : loaded.map.polygons) {
    ASSERT_GE(polygon.cell, 0);
    const auto& box = loaded.map.cells[polygon.cell].bounds;
    const Eigen::Vector3d probe = polygon.centroid + 0.05 * polygon.plane.normal;
    EXPECT_TRUE(box.contains(probe)) << polygon.source_id;
  }
}

#define SKIP_IF_ABSENT(path) \
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << (path)

TEST(IndoorGmlShared, FjkHaus) {
  const std::string path = shared_file("FJK-Haus_IndoorGML_withEXR-corrected_1_0_3.gml");
  SKIP_IF_ABSENT(path);
  const LoadedMap loaded = load_indoorgml(path);
  EXPECT_EQ(loaded.report.version, "1.0.3");
  EXPECT_EQ(loaded.report.cells_by_class.at("CellSpace"), 14);
  EXPECT_EQ(loaded.report.polygons_read, 358);
  EXPECT_EQ(total(loaded.report.polygons_dropped), 0);
  EXPECT_EQ(loaded.report.states, 14);
  EXPECT_EQ(loaded.report.transitions, 30);
  EXPECT_EQ(loaded.map.navigation.nodes.size(), 14u);
  EXPECT_EQ(loaded.map.navigation.edges.size(), 30u);
  // Projected offsets (x ≈ 445 534, y ≈ 5 444 904) moved to the origin, geometry near zero.
  EXPECT_NEAR(loaded.map.origin.x(), 445534.0, 1.0);
  EXPECT_NEAR(loaded.map.origin.y(), 5444897.0, 10.0);
  EXPECT_LT(loaded.map.bounds.max().head<2>().maxCoeff(), 50.0);
  EXPECT_GT(loaded.map.bounds.min().head<2>().minCoeff(), -1.0);
  EXPECT_GE(loaded.map.storeys.size(), 2u);
  EXPECT_LT(loaded.report.planes_after_merge, 358);  // thin walls kept once
  EXPECT_GT(loaded.report.two_sided_faces, 0);
  for (const auto& cell : loaded.map.cells) {
    EXPECT_TRUE(cell.bounds.contains(cell.representative_point + Eigen::Vector3d(0, 0, 1e-9)))
        << cell.id;
  }
}

TEST(IndoorGmlShared, KuCentralPlaza) {
  const std::string path =
      shared_file("KU-Central-Plaza-IndoorGML-PS-without-Texture-04-26-corrected.gml");
  SKIP_IF_ABSENT(path);
  const LoadedMap loaded = load_indoorgml(path);
  const auto& cells = loaded.report.cells_by_class;
  EXPECT_EQ(total(cells), 76);
  EXPECT_EQ(cells.at("GeneralSpace"), 21);
  EXPECT_EQ(cells.at("ConnectionSpace"), 27);
  EXPECT_EQ(cells.at("TransitionSpace"), 2);
  EXPECT_EQ(cells.at("NonNavigableSpace"), 24);
  EXPECT_EQ(cells.at("PublicSafetyRoom"), 2);
  EXPECT_EQ(loaded.report.boundaries, 108);
  EXPECT_EQ(loaded.report.doors, 108);
  EXPECT_GT(loaded.report.door_holes_cut + loaded.report.door_surfaces_removed, 0);
  EXPECT_EQ(loaded.map.navigation.nodes.size(), 76u);
  EXPECT_EQ(loaded.map.navigation.edges.size(), 108u);
  EXPECT_GT(loaded.report.shells_flipped, 0);
  const Eigen::Vector3d size = loaded.map.bounds.sizes();
  EXPECT_GT(size.x(), 40.0);
  EXPECT_LT(size.x(), 70.0);
  EXPECT_GT(size.y(), 100.0);
  EXPECT_LT(size.y(), 130.0);
  int non_navigable = 0;
  for (const auto& cell : loaded.map.cells) non_navigable += cell.navigable ? 0 : 1;
  EXPECT_EQ(non_navigable, 24);
}

TEST(IndoorGmlShared, Pnu2dExtrusion) {
  const std::string path = shared_file("PNU-bldg313-4F-2D-190612.gml");
  SKIP_IF_ABSENT(path);
  MapLoadOptions options;
  options.storey_height_m = 2.7;
  const LoadedMap loaded = load_indoorgml(path, options);
  EXPECT_TRUE(loaded.report.extruded_2d);
  EXPECT_EQ(total(loaded.report.cells_by_class), 30);
  EXPECT_EQ(loaded.report.polygons_read, 30);
  EXPECT_NEAR(loaded.map.bounds.min().z(), 0.0, 1e-9);
  EXPECT_NEAR(loaded.map.bounds.max().z(), 2.7, 1e-9);
  EXPECT_NEAR(loaded.map.bounds.min().x(), 3.55, 0.01);
  EXPECT_NEAR(loaded.map.bounds.max().y(), 297.30, 0.01);
  ASSERT_EQ(loaded.map.storeys.size(), 1u);
  EXPECT_EQ(loaded.map.navigation.nodes.size(), 30u);
  EXPECT_GT(loaded.map.navigation.edges.size(), 20u);  // from shared boundaries: no transitions
  EXPECT_GT(loaded.report.two_sided_faces, 0);
}

TEST(IndoorGmlShared, PutOuterContradictedGeographicLabel) {
  const std::string path = shared_file("put-outer_examples_03_model.gml");
  SKIP_IF_ABSENT(path);
  const LoadedMap loaded = load_indoorgml(path);
  EXPECT_EQ(loaded.report.version, "1.0.1");
  EXPECT_EQ(total(loaded.report.cells_by_class), 7);
  ASSERT_FALSE(loaded.report.warnings.empty());
  EXPECT_NE(loaded.report.warnings.front().find("4326"), std::string::npos);
  // The values win: metres 0..50, not degrees.
  EXPECT_NEAR(loaded.map.bounds.max().x(), 49.936, 0.01);
  EXPECT_NEAR(loaded.map.bounds.max().y(), 49.736, 0.01);
  // Its second space layer ("lights") holds the lights' ranges drawn over the three rooms of
  // "topology": no walls (they crossed the rooms and fenced the route in).
  EXPECT_EQ(loaded.report.cells_left_out, 4);
  EXPECT_EQ(loaded.map.cells.size(), 3u);
  EXPECT_EQ(loaded.report.planes_after_merge, 21);
  EXPECT_EQ(loaded.map.navigation.nodes.size(), 3u);
  EXPECT_NEAR(loaded.map.bounds.max().z(), 3.0, 1e-9);
  EXPECT_TRUE(loaded.map.origin.isZero());
}

TEST(IndoorGmlVersions, Form101UnclosedRingsRepeatedVertexPosList) {
  const LoadedMap loaded = load_indoorgml(test_file("v101_room.gml"));
  EXPECT_EQ(loaded.report.version, "1.0.1");
  EXPECT_EQ(loaded.report.polygons_read, 6);
  EXPECT_EQ(loaded.report.planes_after_merge, 6);
  EXPECT_TRUE(loaded.map.bounds.min().isApprox(Eigen::Vector3d(0, 0, 0)));
  EXPECT_TRUE(loaded.map.bounds.max().isApprox(Eigen::Vector3d(4, 3, 2.5)));
  for (const auto& polygon : loaded.map.polygons) EXPECT_EQ(polygon.outer.size(), 4u);
  expect_normals_into_cells(loaded);
  ASSERT_EQ(loaded.map.cells.size(), 1u);
  EXPECT_EQ(loaded.map.cells[0].name, "Room 1");
  EXPECT_NEAR(std::abs(conicloc::maps::signed_area(loaded.map.cells[0].footprint)), 12.0, 1e-9);
}

TEST(IndoorGmlVersions, Form20LayersAndDualSpace) {
  const LoadedMap loaded = load_indoorgml(test_file("v20_room.gml"));
  EXPECT_EQ(loaded.report.version, "2.0");
  EXPECT_EQ(loaded.report.planes_after_merge, 6);
  EXPECT_EQ(loaded.report.states, 1);
  ASSERT_EQ(loaded.map.navigation.nodes.size(), 1u);
  EXPECT_EQ(loaded.map.navigation.nodes[0].id, "N1");
  // The Node's point is inside the cell: it is the representative point, at floor level.
  EXPECT_TRUE(loaded.map.cells[0].representative_point.isApprox(Eigen::Vector3d(2, 2, 0)));
  expect_normals_into_cells(loaded);
}

TEST(IndoorGmlGeometry, TwoRoomsInwardShellHolesOrientableHrefDoor) {
  const LoadedMap loaded = load_indoorgml(test_file("v103_two_rooms_door.gml"));
  EXPECT_EQ(loaded.report.version, "1.0.3");
  EXPECT_EQ(loaded.report.cells_by_class.at("GeneralSpace"), 2);
  EXPECT_EQ(loaded.report.polygons_read, 12);  // 11 inline + 1 through xlink:href
  // 12 faces; the thin wall x = 4 is held once, two-sided; the door is an opening in it.
  EXPECT_EQ(loaded.report.planes_after_merge, 11);
  EXPECT_EQ(loaded.report.two_sided_faces, 1);
  EXPECT_EQ(loaded.report.doors, 1);
  int walls_with_window = 0;
  for (const auto& polygon : loaded.map.polygons) {
    if (polygon.source_id == "A-south") {
      ++walls_with_window;
      ASSERT_EQ(polygon.holes.size(), 1u);
      EXPECT_NEAR(polygon.area, 9.0, 1e-9);
    }
    if (std::abs(polygon.centroid.x() - 4.0) < 1e-9) {
      EXPECT_TRUE(polygon.two_sided);
      EXPECT_EQ(polygon.holes.size(), 1u);  // the door
      EXPECT_NEAR(polygon.area, 7.5 - 2.0, 1e-9);
      EXPECT_FALSE(polygon.contains_uv(polygon.frame.project({4.0, 1.5, 1.0})));
      EXPECT_TRUE(polygon.contains_uv(polygon.frame.project({4.0, 0.5, 1.0})));
    }
  }
  EXPECT_EQ(walls_with_window, 1);
  // Room A's rings were written inward, room B's outward, B's west wall through an
  // OrientableSurface "-": all normals face into their cells.
  expect_normals_into_cells(loaded);
  ASSERT_EQ(loaded.map.navigation.edges.size(), 1u);
  const auto& edge = loaded.map.navigation.edges[0];
  EXPECT_TRUE(edge.through_door);
  EXPECT_TRUE(edge.door_point.isApprox(Eigen::Vector3d(4, 1.5, 1)));
  EXPECT_NEAR(edge.weight_m, 4.5, 1e-9);
  EXPECT_TRUE(loaded.map.navigation.nodes[0].position.isApprox(Eigen::Vector3d(1.5, 1.5, 0)));
}

TEST(IndoorGmlGeometry, CloseDoorsKeepsTheDoorAsWall) {
  MapLoadOptions options;
  options.close_doors = true;
  const LoadedMap loaded = load_indoorgml(test_file("v103_two_rooms_door.gml"), options);
  for (const auto& polygon : loaded.map.polygons) {
    if (std::abs(polygon.centroid.x() - 4.0) < 1e-9) {
      EXPECT_TRUE(polygon.holes.empty());
      EXPECT_NEAR(polygon.area, 7.5, 1e-9);
    }
  }
}

TEST(IndoorGmlGeometry, TwoDimensionalExtrusionAndMerge) {
  MapLoadOptions options;
  options.storey_height_m = 2.5;
  const LoadedMap loaded = load_indoorgml(test_file("flat_2d.gml"), options);
  EXPECT_TRUE(loaded.report.extruded_2d);
  // Two cells: 4 walls + floor + ceiling each, the shared wall x = 5 once, two-sided.
  EXPECT_EQ(loaded.report.planes_after_merge, 11);
  EXPECT_EQ(loaded.report.two_sided_faces, 1);
  EXPECT_TRUE(loaded.map.bounds.max().isApprox(Eigen::Vector3d(9, 4, 2.5)));
  expect_normals_into_cells(loaded);
  ASSERT_EQ(loaded.map.navigation.edges.size(), 1u);  // from the shared boundary B1 / B1-REVERSE
  EXPECT_FALSE(loaded.map.navigation.edges[0].through_door);
  EXPECT_TRUE(loaded.map.navigation.edges[0].door_point.isApprox(Eigen::Vector3d(5, 2, 0)));
}

}  // namespace
