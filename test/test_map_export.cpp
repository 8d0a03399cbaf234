// OBJ and SVG exports of a PlaneMap, and the horizontal sections the floor plan is drawn from.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <pugixml.hpp>
#include <sstream>

#include "io/input_error.hpp"
#include "io/map_export.hpp"
#include "maps/polygon_section.hpp"
#include "test/temp_path.hpp"

namespace cm = conicloc::maps;
namespace ci = conicloc::io;

namespace {

cm::PlanarPolygon polygon(const cm::Ring3& outer, const std::vector<cm::Ring3>& holes = {}) {
  cm::PlanarPolygon p;
  EXPECT_TRUE(cm::make_planar_polygon(outer, holes, p));
  return p;
}

// South wall (y = 0) of a 6 m room, outward normal -y: a door notch at x 2.5..3.4 and a window
// hole at x 4..5.5, z 0.9..2.1 (the layout of examples/example_building.gml).
cm::PlanarPolygon wall_with_door_and_window(double z0) {
  return polygon({{6, 0, z0},
                  {4.5, 0, z0},
                  {3.4, 0, z0},
                  {3.4, 0, z0 + 2.1},
                  {2.5, 0, z0 + 2.1},
                  {2.5, 0, z0},
                  {0, 0, z0},
                  {0, 0, z0 + 3},
                  {6, 0, z0 + 3}},
                 {{{4, 0, z0 + 0.9}, {5.5, 0, z0 + 0.9}, {5.5, 0, z0 + 2.1}, {4, 0, z0 + 2.1}}});
}

// Two storeys, one 6 m x 4 m room each (floor, ceiling, four walls), joined by a graph edge.
cm::PlaneMap two_room_map() {
  cm::PlaneMap map;
  for (int s = 0; s < 2; ++s) {
    const double z0 = 3.2 * s, z1 = z0 + 3.0;
    map.storeys.push_back({"level " + std::to_string(s), z0, z1});
    cm::Cell cell;
    cell.id = "room-" + std::to_string(s);
    cell.name = s == 0 ? "Room <A> & co" : "Room B";  // escaped in SVG
    cell.class_name = "GeneralSpace";
    cell.storey = s;
    cell.floor_z = z0;
    cell.ceiling_z = z1;
    cell.footprint = {{0, 0}, {6, 0}, {6, 4}, {0, 4}};
    cell.representative_point = {3, 2, z0};
    const int c = static_cast<int>(map.cells.size());
    std::vector<cm::PlanarPolygon> faces = {
        polygon({{0, 0, z0}, {0, 4, z0}, {6, 4, z0}, {6, 0, z0}}),
        polygon({{0, 0, z1}, {6, 0, z1}, {6, 4, z1}, {0, 4, z1}}),
        wall_with_door_and_window(z0),
        polygon({{6, 0, z0}, {6, 4, z0}, {6, 4, z1}, {6, 0, z1}}),
        polygon({{6, 4, z0}, {0, 4, z0}, {0, 4, z1}, {6, 4, z1}}),
        polygon({{0, 4, z0}, {0, 0, z0}, {0, 0, z1}, {0, 4, z1}})};
    for (auto& f : faces) {
      f.cell = c;
      f.storey = s;
      cell.polygons.push_back(static_cast<int>(map.polygons.size()));
      map.polygons.push_back(std::move(f));
    }
    map.cells.push_back(cell);
    map.navigation.nodes.push_back({"S" + std::to_string(s), c, {3, 2, z0 + 0.5}});
  }
  cm::NavEdge door;
  door.id = "T0";
  door.from = 0;
  door.to = 1;
  door.through_door = true;
  door.door_point = {2.95, 0, 0.5};
  map.navigation.edges.push_back(door);
  for (const auto& p : map.polygons) map.bounds.extend(p.bounds);
  return map;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

double triangle_area(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return 0.5 * (b - a).cross(c - a).norm();
}

}  // namespace

TEST(HorizontalSection, DoorNotchLeavesAGapAndWindowIsAnOpening) {
  const auto wall = wall_with_door_and_window(0.0);
  auto pieces = cm::horizontal_section(wall, 1.0);
  ASSERT_EQ(pieces.size(), 3u);  // 0..2.5, 3.4..4, 5.5..6
  double covered = 0.0;
  for (const auto& s : pieces) {
    EXPECT_NEAR(s.a.z(), 1.0, 1e-12);
    EXPECT_NEAR(s.b.y(), 0.0, 1e-12);
    covered += (s.b - s.a).norm();
  }
  EXPECT_NEAR(covered, 2.5 + 0.6 + 0.5, 1e-9);
  const auto windows = cm::horizontal_section_of_holes(wall, 1.0);
  ASSERT_EQ(windows.size(), 1u);
  EXPECT_NEAR((windows[0].b - windows[0].a).norm(), 1.5, 1e-9);
  // Above the door and window: the whole wall.
  pieces = cm::horizontal_section(wall, 2.5);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_NEAR((pieces[0].b - pieces[0].a).norm(), 6.0, 1e-9);
  EXPECT_TRUE(cm::horizontal_section(wall, 3.5).empty());
}

TEST(HorizontalSection, FloorsHaveNoneAndSlopesAreCutWhereTheyReachTheHeight) {
  const auto floor = polygon({{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}});
  EXPECT_TRUE(cm::horizontal_section(floor, 0.0).empty());
  // Ramp rising 2 m over x 0..4: z = 1 at x = 2.
  const auto ramp = polygon({{0, 0, 0}, {4, 0, 2}, {4, 3, 2}, {0, 3, 0}});
  const auto pieces = cm::horizontal_section(ramp, 1.0);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_NEAR(pieces[0].a.x(), 2.0, 1e-9);
  EXPECT_NEAR(pieces[0].b.x(), 2.0, 1e-9);
  EXPECT_NEAR((pieces[0].b - pieces[0].a).norm(), 3.0, 1e-9);
}

TEST(ObjExport, CountsParseBackAndAreaIsKept) {
  const auto map = two_room_map();
  std::ostringstream out;
  const auto stats = ci::write_obj(map, out, "rooms.mtl");
  std::istringstream in(out.str());
  std::vector<Eigen::Vector3d> vertices;
  int normals = 0, faces = 0, objects = 0, groups = 0, mtllib = 0;
  double area = 0.0;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "v") {
      Eigen::Vector3d v;
      ASSERT_TRUE(fields >> v.x() >> v.y() >> v.z());
      vertices.push_back(v);
    } else if (tag == "vn") {
      ++normals;
    } else if (tag == "f") {
      std::array<Eigen::Vector3d, 3> corner;
      for (auto& c : corner) {
        std::string token;
        ASSERT_TRUE(fields >> token);
        const int index = std::stoi(token.substr(0, token.find('/')));
        ASSERT_GE(index, 1);
        ASSERT_LE(index, static_cast<int>(vertices.size()));  // refers back only
        const int normal = std::stoi(token.substr(token.rfind('/') + 1));
        ASSERT_GE(normal, 1);
        ASSERT_LE(normal, normals);
        c = vertices[static_cast<std::size_t>(index - 1)];
      }
      area += triangle_area(corner[0], corner[1], corner[2]);
      ++faces;
    } else if (tag == "o") {
      ++objects;
    } else if (tag == "g") {
      ++groups;
    } else if (tag == "mtllib") {
      ++mtllib;
    }
  }
  EXPECT_EQ(static_cast<int>(vertices.size()), stats.vertices);
  EXPECT_EQ(normals, stats.normals);
  EXPECT_EQ(faces, stats.faces);
  EXPECT_EQ(objects, 2);     // one per cell
  EXPECT_EQ(groups, 2 * 3);  // floor, ceiling, wall per cell
  EXPECT_EQ(stats.groups, groups);
  EXPECT_EQ(mtllib, 1);
  double expected = 0.0;
  for (const auto& p : map.polygons) expected += p.area;
  EXPECT_NEAR(area, expected, 1e-6);  // holes and notches stay open
  EXPECT_NEAR(expected, 2 * (24 + 24 + 18 + 12 + 18 + 12 - 0.9 * 2.1 - 1.5 * 1.2), 1e-9);
}

TEST(ObjExport, FileAndMaterialsAreWrittenOrTheErrorNamesThePath) {
  const auto map = two_room_map();
  const auto dir = conicloc::test::unique_temp_path("map_export");
  std::filesystem::create_directories(dir);
  const auto obj = dir / "rooms.obj";
  const auto stats = ci::write_obj_file(map, obj.string());
  EXPECT_GT(stats.faces, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "rooms.mtl"));
  std::ifstream in(obj);
  std::string first_lines((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(first_lines.find("mtllib rooms.mtl"), std::string::npos);
  std::filesystem::remove_all(dir);
  try {
    ci::write_obj_file(map, "/nonexistent-dir/x.obj");
    FAIL() << "expected InputError";
  } catch (const ci::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x."), std::string::npos);
  }
}

TEST(SvgFloorPlan, WellFormedWithOneGroupPerStoreyAndAllParts) {
  const auto map = two_room_map();
  const std::string svg = ci::render_floor_plan_svg(map);
  pugi::xml_document doc;
  const auto parsed = doc.load_string(svg.c_str());
  ASSERT_TRUE(parsed) << parsed.description() << " at offset " << parsed.offset;
  const auto root = doc.child("svg");
  ASSERT_TRUE(root);
  int storeys = 0;
  for (const auto& g : root.children("g")) {
    if (std::string(g.attribute("class").value()) != "storey") continue;
    ++storeys;
    const auto walls = g.find_child_by_attribute("g", "class", "walls");
    // Cut at 1 m: the door notch splits the south wall, the window hole too: 3 + 3 walls.
    EXPECT_EQ(std::distance(walls.children("line").begin(), walls.children("line").end()), 6);
    const auto windows = g.find_child_by_attribute("g", "class", "windows");
    EXPECT_EQ(std::distance(windows.children("line").begin(), windows.children("line").end()), 2);
    const auto cells = g.find_child_by_attribute("g", "class", "cells");
    EXPECT_EQ(std::distance(cells.children("polygon").begin(), cells.children("polygon").end()), 1);
  }
  EXPECT_EQ(storeys, 2);
  EXPECT_TRUE(root.find_child_by_attribute("g", "class", "scale-bar"));
  EXPECT_TRUE(root.find_child_by_attribute("g", "class", "north-arrow"));
  EXPECT_EQ(count(svg, "Room &lt;A&gt; &amp; co"), 1u);
  // The door (at z 0.5) is drawn on storey 0 only, along the wall (y = 0 in the map frame).
  const auto storey0 = root.find_child_by_attribute("g", "id", "storey-0");
  const auto doors = storey0.find_child_by_attribute("g", "class", "doors");
  const auto door = doors.child("line");
  ASSERT_TRUE(door);
  EXPECT_EQ(std::string(door.attribute("y1").value()), door.attribute("y2").value());
  const auto storey1 = root.find_child_by_attribute("g", "id", "storey-1");
  EXPECT_FALSE(storey1.find_child_by_attribute("g", "class", "doors").child("line"));
}

TEST(SvgFloorPlan, NorthIsUp) {
  auto map = two_room_map();
  map.storeys.resize(1);
  ci::FloorPlanOptions options;
  options.pixels_per_m = 10.0;
  options.show_navigation = false;
  options.show_labels = false;
  const std::string svg = ci::render_floor_plan_svg(map, options);
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(svg.c_str()));
  // The south wall (y = 0) is the lowest line on the page: the largest SVG y.
  double max_y = -1.0, south_y = -1.0;
  for (const auto& line : doc.child("svg")
                              .find_child_by_attribute("g", "class", "storey")
                              .find_child_by_attribute("g", "class", "walls")
                              .children("line")) {
    const double y1 = line.attribute("y1").as_double();
    const double y2 = line.attribute("y2").as_double();
    max_y = std::max(max_y, y1);
    if (y1 == y2 && line.attribute("x2").as_double() - line.attribute("x1").as_double() != 0.0 &&
        south_y < y1) {
      south_y = y1;
    }
  }
  EXPECT_EQ(south_y, max_y);
  EXPECT_GT(south_y, 40.0);  // 4 m at 10 px/m below the top of the plan
}

TEST(SvgFloorPlan, EmptyMapStillRenders) {
  const std::string svg = ci::render_floor_plan_svg(cm::PlaneMap{});
  pugi::xml_document doc;
  EXPECT_TRUE(doc.load_string(svg.c_str()));
  EXPECT_NE(svg.find("empty map"), std::string::npos);
}
