// Navigable cells whose model holds no floor take their floor from the cells they open into
// (maps/floorless_cells.hpp), on the two-room box building with room B's floor taken away.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "io/indoorgml.hpp"
#include "localizer/filter/free_space.hpp"
#include "maps/floorless_cells.hpp"
#include "maps/walkable_ground.hpp"
#include "shared_buildings.hpp"
#include "sim/box_building.hpp"

namespace {

using conicloc::maps::PlaneMap;

// Room B (cell 1) without its floor, its lowest vertex (Cell::floor_z) at `foot_z`, as if its
// walls reached below the door it shares with room A (floor at 0).
PlaneMap box_without_floor_in_b(double foot_z) {
  PlaneMap map = conicloc::sim::make_box_building();
  auto& polygons = map.cells[1].polygons;
  polygons.erase(
      std::remove_if(
          polygons.begin(), polygons.end(),
          [&](int p) { return map.polygons[static_cast<std::size_t>(p)].source_id == "B-floor"; }),
      polygons.end());
  map.cells[1].floor_z = foot_z;
  map.cells[1].representative_point.z() = foot_z;
  for (auto& node : map.navigation.nodes) {
    if (node.cell == 1) node.position.z() = foot_z;
  }
  return map;
}

TEST(FloorlessCells, RoomsWithFloorsAreLeftAsTheyAre) {
  PlaneMap map = conicloc::sim::make_box_building();
  ASSERT_TRUE(conicloc::maps::cell_has_floor(map, 0));
  ASSERT_TRUE(conicloc::maps::cell_has_floor(map, 1));
  std::vector<std::string> warnings;
  EXPECT_EQ(conicloc::maps::assign_floors_to_floorless_cells(map, warnings), 0);
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(map.cells[0].floor_z, 0.0);
  EXPECT_EQ(map.cells[1].floor_z, 0.0);
}

TEST(FloorlessCells, AFloorlessRoomStandsAtTheFloorOfTheRoomItOpensInto) {
  PlaneMap map = box_without_floor_in_b(-0.27);
  ASSERT_FALSE(conicloc::maps::cell_has_floor(map, 1));
  std::vector<std::string> warnings;
  conicloc::maps::assign_floors_to_floorless_cells(map, warnings);
  EXPECT_EQ(map.cells[1].floor_z, 0.0);
  EXPECT_EQ(map.cells[1].representative_point.z(), 0.0);
  for (const auto& node : map.navigation.nodes) {
    if (node.cell == 1) {
      EXPECT_EQ(node.position.z(), 0.0);
    }
  }
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("\"" + map.cells[1].id + "\""), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("-0.270"), std::string::npos) << warnings[0];
  EXPECT_EQ(map.cells[0].floor_z, 0.0);  // room A had its floor
  // The free space now puts a sensor in B at A's floor, not 0.27 m below.
  const conicloc::localizer::FreeSpace free_space(map);
  const int cell = free_space.cell_at(7.5, 2.0, 0.8);
  EXPECT_EQ(cell, 1);
  EXPECT_EQ(free_space.floor_z_at(cell, 7.5, 2.0, 0.8), 0.0);
}

TEST(FloorlessCells, TheThresholdIsTheNeighboursGroundNotItsLowestVertex) {
  PlaneMap map = box_without_floor_in_b(-0.27);
  map.cells[0].floor_z = -5.0;  // A's lowest vertex far below its floor (a sloped cell's low end)
  std::vector<std::string> warnings;
  EXPECT_EQ(conicloc::maps::assign_floors_to_floorless_cells(map, warnings), 1);
  EXPECT_EQ(map.cells[1].floor_z, 0.0);
}

TEST(FloorlessCells, APillarTopUnderTheCeilingIsNoFloor) {
  // An upward face 0.5 m under B's ceiling (3 m): the top of a pillar, not ground to stand on,
  // for the map's floorless cells as for the localizer's free space.
  PlaneMap map = box_without_floor_in_b(-0.27);
  conicloc::maps::PlanarPolygon top;
  ASSERT_TRUE(conicloc::maps::make_planar_polygon(
      {{7, 1, 2.5}, {8, 1, 2.5}, {8, 2, 2.5}, {7, 2, 2.5}}, {}, top));
  if (top.plane.normal.z() < 0.0) {
    ASSERT_TRUE(conicloc::maps::make_planar_polygon(
        {{7, 2, 2.5}, {8, 2, 2.5}, {8, 1, 2.5}, {7, 1, 2.5}}, {}, top));
  }
  top.cell = 1;
  map.polygons.push_back(top);
  map.cells[1].polygons.push_back(static_cast<int>(map.polygons.size()) - 1);
  EXPECT_FALSE(conicloc::maps::cell_has_floor(map, 1));
  std::vector<std::string> warnings;
  EXPECT_EQ(conicloc::maps::assign_floors_to_floorless_cells(map, warnings), 1);
  const conicloc::localizer::FreeSpace free_space(map);
  EXPECT_EQ(free_space.floor_z_at(1, 7.5, 1.5, 0.8), 0.0);
}

TEST(FloorlessCells, WithoutANeighbourWithAFloorTheLowestVertexStays) {
  PlaneMap map = box_without_floor_in_b(-0.27);
  map.navigation.edges.clear();
  std::vector<std::string> warnings;
  conicloc::maps::assign_floors_to_floorless_cells(map, warnings);
  EXPECT_EQ(map.cells[1].floor_z, -0.27);
  EXPECT_TRUE(warnings.empty());
}

TEST(FloorlessCells, ANeighbourFloorAboveTheRoomIsNoThresholdOfIt) {
  // B wholly below A (from -3.5 to -0.5 m): A's floor is no threshold B is entered at.
  PlaneMap map = box_without_floor_in_b(-3.5);
  map.cells[1].ceiling_z = -0.5;
  std::vector<std::string> warnings;
  conicloc::maps::assign_floors_to_floorless_cells(map, warnings);
  EXPECT_EQ(map.cells[1].floor_z, -3.5);
  EXPECT_TRUE(warnings.empty());
}

TEST(FloorlessCells, KuCentralPlazaRoomsEnteredAtTheirDoors) {
  const auto path = conicloc::test::shared_indoorgml_dir() /
                    "KU-Central-Plaza-IndoorGML-PS-without-Texture-04-26-corrected.gml";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  const auto loaded = conicloc::io::load_indoorgml(path.string());
  const PlaneMap& map = loaded.map;
  // ROOM15 and ROOM16 have no floor surface; their walls reach 0.27 m below their doors, whose
  // cells' floors (DOOR4 from -1.341 m, DOOR3 from -1.359 m) rise by 2.4 cm across them.
  for (const auto& [room, door_floor_z] :
       {std::pair<std::string, double>{"ROOM15", -1.341}, {"ROOM16", -1.359}}) {
    const auto cell = std::find_if(map.cells.begin(), map.cells.end(),
                                   [&](const auto& c) { return c.id == room; });
    ASSERT_NE(cell, map.cells.end()) << room;
    EXPECT_FALSE(conicloc::maps::cell_has_floor(map, static_cast<int>(cell - map.cells.begin())));
    EXPECT_GE(cell->floor_z, door_floor_z) << room;
    EXPECT_LE(cell->floor_z, door_floor_z + 0.024) << room;
    EXPECT_LT(cell->bounds.min().z(), door_floor_z - 0.25) << room;
    const auto warned = std::count_if(
        loaded.report.warnings.begin(), loaded.report.warnings.end(),
        [&](const std::string& w) { return w.find("\"" + room + "\" has no floor") != w.npos; });
    EXPECT_EQ(warned, 1) << room;
  }
}

}  // namespace
