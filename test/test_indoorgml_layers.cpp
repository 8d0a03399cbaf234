// IndoorGML space layers: only the topographic layer's cells bound physical space. A second layer
// of coverage zones drawn over the rooms (test/data v103_two_rooms_door.gml plus one cell) must not
// add walls; a second layer of rooms beside the first, and obstacles in any layer, must stay.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "io/indoorgml.hpp"
#include "test/temp_path.hpp"

namespace {

using conicloc::io::load_indoorgml;
using conicloc::io::LoadedMap;

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The six faces of the box x0..x1 × 0.5..2.5 × 0..2.5 as GML surface members.
std::string box_shell(double x0, double x1) {
  const auto pos = [](double x, double y, double z) {
    std::ostringstream p;
    p << "<gml:pos>" << x << " " << y << " " << z << "</gml:pos>";
    return p.str();
  };
  const auto face = [&](const std::vector<std::array<double, 3>>& corners) {
    std::string ring;
    for (const auto& c : corners) ring += pos(c[0], c[1], c[2]);
    ring += pos(corners[0][0], corners[0][1], corners[0][2]);
    return "<gml:surfaceMember><gml:Polygon><gml:exterior><gml:LinearRing>" + ring +
           "</gml:LinearRing></gml:exterior></gml:Polygon></gml:surfaceMember>";
  };
  const double y0 = 0.5, y1 = 2.5, h = 2.5;
  return face({{x0, y0, 0}, {x0, y1, 0}, {x1, y1, 0}, {x1, y0, 0}}) +  // floor
         face({{x0, y0, h}, {x1, y0, h}, {x1, y1, h}, {x0, y1, h}}) +  // ceiling
         face({{x0, y0, 0}, {x1, y0, 0}, {x1, y0, h}, {x0, y0, h}}) +
         face({{x1, y0, 0}, {x1, y1, 0}, {x1, y1, h}, {x1, y0, h}}) +
         face({{x1, y1, 0}, {x0, y1, 0}, {x0, y1, h}, {x1, y1, h}}) +
         face({{x0, y1, 0}, {x0, y0, 0}, {x0, y0, h}, {x0, y1, h}});
}

// A 1.0 box cell x0..x1 (box_shell) named `id`, dual to state "S" + id, of element `element`
// (qualified: "nv:GeneralSpace", "ns0:CellSpace").
std::string box_cell(const std::string& id, double x0, double x1, const std::string& element) {
  return "<ns0:cellSpaceMember><" + element + " gml:id=\"" + id +
         "\"><ns0:cellSpaceGeometry><ns0:Geometry3D><gml:Solid><gml:exterior><gml:Shell>" +
         box_shell(x0, x1) +
         "</gml:Shell></gml:exterior></gml:Solid></ns0:Geometry3D></ns0:cellSpaceGeometry>" +
         "<ns0:duality xlink:href=\"#S" + id + "\"/></" + element + "></ns0:cellSpaceMember>";
}

// The two-room model with `cell` added and a second space layer "wifi" holding its state (listed
// after the rooms' layer, or before it); `layer_class` is written as its class when not empty.
LoadedMap load_with_second_layer(const std::string& cell, const std::string& id,
                                 const std::string& layer_class, bool listed_first = false) {
  std::string text =
      read_text(std::string(CONICLOC_TEST_DATA) + "/indoorgml/v103_two_rooms_door.gml");
  const std::string cells_end = "<ns0:cellSpaceBoundaryMember>";
  text.insert(text.find(cells_end), cell);
  const std::string layers_end = "</ns0:spaceLayers>";
  const std::string layer =
      "<ns0:spaceLayerMember><ns0:SpaceLayer gml:id=\"wifi\">" +
      (layer_class.empty() ? "" : "<ns0:class>" + layer_class + "</ns0:class>") +
      "<ns0:nodes gml:id=\"NW\"><ns0:stateMember><ns0:State gml:id=\"S" + id +
      "\"><ns0:duality xlink:href=\"#" + id +
      "\"/></ns0:State></ns0:stateMember></ns0:nodes></ns0:SpaceLayer></ns0:spaceLayerMember>";
  text.insert(listed_first ? text.find("<ns0:spaceLayerMember>") : text.find(layers_end), layer);
  const auto path = conicloc::test::unique_temp_path("layers.gml");
  std::ofstream(path) << text;
  LoadedMap loaded = load_indoorgml(path.string());
  std::filesystem::remove(path);
  return loaded;
}

bool has_cell(const LoadedMap& loaded, const std::string& id) {
  for (const auto& cell : loaded.map.cells) {
    if (cell.id == id) return true;
  }
  return false;
}

TEST(IndoorGmlLayers, ZonesOverTheRoomsAreNoWalls) {
  // A coverage zone across both rooms and the wall between them: without the layer selection its
  // six faces would stand in the rooms as walls, floor and ceiling.
  const LoadedMap loaded =
      load_with_second_layer(box_cell("Z", 1.0, 7.0, "nv:GeneralSpace"), "Z", "");
  EXPECT_FALSE(has_cell(loaded, "Z"));
  EXPECT_EQ(loaded.map.cells.size(), 2u);
  EXPECT_EQ(loaded.report.planes_after_merge, 11);  // the two rooms' alone
  EXPECT_EQ(loaded.report.cells_left_out, 1);
  ASSERT_EQ(loaded.report.space_layer_notes.size(), 1u);
  EXPECT_NE(loaded.report.space_layer_notes[0].find("\"wifi\""), std::string::npos);
  EXPECT_EQ(loaded.map.navigation.nodes.size(), 2u);
}

TEST(IndoorGmlLayers, RoomsOfAnotherLayerBesideTheFirstStay) {
  const LoadedMap loaded =
      load_with_second_layer(box_cell("Z", 9.0, 12.0, "nv:GeneralSpace"), "Z", "");
  EXPECT_TRUE(has_cell(loaded, "Z"));
  EXPECT_EQ(loaded.report.cells_left_out, 0);
  EXPECT_EQ(loaded.report.planes_after_merge, 11 + 6);
}

TEST(IndoorGmlLayers, ObstaclesInAnotherLayerStay) {
  // A column inside room A, in a layer of its own: a real obstacle, whatever its layer — named
  // non-navigable, or a plain CellSpace as core-only files name every cell (it crosses no wall).
  for (const char* element : {"nv:NonNavigableSpace", "ns0:CellSpace"}) {
    const LoadedMap loaded = load_with_second_layer(box_cell("C", 1.5, 2.0, element), "C", "");
    EXPECT_TRUE(has_cell(loaded, "C")) << element;
    EXPECT_EQ(loaded.report.cells_left_out, 0) << element;
  }
}

TEST(IndoorGmlLayers, ADeclaredSensorLayerIsLeftOutWherever) {
  const LoadedMap loaded =
      load_with_second_layer(box_cell("Z", 9.0, 12.0, "nv:GeneralSpace"), "Z", " SENSOR ");
  EXPECT_FALSE(has_cell(loaded, "Z"));
  ASSERT_EQ(loaded.report.space_layer_notes.size(), 1u);
  EXPECT_NE(loaded.report.space_layer_notes[0].find("SENSOR"), std::string::npos);
}

TEST(IndoorGmlLayers, ADeclaredTopographicLayerIsKept) {
  const LoadedMap loaded =
      load_with_second_layer(box_cell("Z", 1.0, 7.0, "nv:GeneralSpace"), "Z", "TOPOGRAPHIC");
  EXPECT_TRUE(has_cell(loaded, "Z"));
}

// The 2.0 one-room model (test/data v20_room.gml: 0..5 × 0..4 × 0..3) with a second
// ThematicLayer holding the box cell x0..x1 (box_shell); `theme` written when not empty.
LoadedMap load_20_with_second_layer(double x0, double x1, const std::string& theme) {
  std::string text = read_text(std::string(CONICLOC_TEST_DATA) + "/indoorgml/v20_room.gml");
  const std::string layer =
      "<core:ThematicLayer gml:id=\"TL2\">" +
      (theme.empty() ? "" : "<core:theme>" + theme + "</core:theme>") +
      "<core:primalSpace><core:PrimalSpaceLayer gml:id=\"PSL2\"><core:cellSpaceMember>"
      "<core:CellSpace gml:id=\"Z\"><core:cellSpaceGeom><core:CellSpaceGeometry><core:geometry3D>"
      "<gml:Solid><gml:exterior><gml:Shell>" +
      box_shell(x0, x1) +
      "</gml:Shell></gml:exterior></gml:Solid></core:geometry3D></core:CellSpaceGeometry>"
      "</core:cellSpaceGeom></core:CellSpace></core:cellSpaceMember></core:PrimalSpaceLayer>"
      "</core:primalSpace></core:ThematicLayer>";
  text.insert(text.find("</core:layers>"), layer);
  const auto path = conicloc::test::unique_temp_path("layers20.gml");
  std::ofstream(path) << text;
  LoadedMap loaded = load_indoorgml(path.string());
  std::filesystem::remove(path);
  return loaded;
}

}  // namespace

TEST(IndoorGmlLayers, ASensorLayerListedFirstIsNotTakenForTheRooms) {
  const LoadedMap loaded =
      load_with_second_layer(box_cell("Z", 1.0, 7.0, "nv:GeneralSpace"), "Z", "SENSOR", true);
  EXPECT_TRUE(has_cell(loaded, "A"));
  EXPECT_TRUE(has_cell(loaded, "B"));
  EXPECT_FALSE(has_cell(loaded, "Z"));
  EXPECT_EQ(loaded.report.doors, 1);
}

TEST(IndoorGmlLayers, AnUnknownClassIsJudgedByGeometry) {
  EXPECT_FALSE(has_cell(
      load_with_second_layer(box_cell("Z", 1.0, 7.0, "nv:GeneralSpace"), "Z", "UNKNOWN"), "Z"));
  EXPECT_TRUE(has_cell(
      load_with_second_layer(box_cell("Z", 9.0, 12.0, "nv:GeneralSpace"), "Z", "UNKNOWN"), "Z"));
}

TEST(IndoorGmlLayers, Form20ThematicLayersByTheme) {
  // Cells in a second ThematicLayer, known by where they are written (no dual nodes). Neither
  // layer has doors: without a theme the file does not say which is the building.
  EXPECT_FALSE(has_cell(load_20_with_second_layer(1.0, 4.0, "Virtual"), "Z"));
  EXPECT_TRUE(has_cell(load_20_with_second_layer(1.0, 4.0, "Physical"), "Z"));
  const LoadedMap undeclared = load_20_with_second_layer(1.0, 4.0, "");
  EXPECT_TRUE(has_cell(undeclared, "Z"));
  ASSERT_EQ(undeclared.report.space_layer_notes.size(), 1u);
  EXPECT_NE(undeclared.report.space_layer_notes[0].find("every cell kept"), std::string::npos);
}
