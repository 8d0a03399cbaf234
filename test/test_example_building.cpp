// The shipped example building: in sync with its generator script, loads into the layout it was
// designed with, and exports, triangulates and indexes cleanly.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <pugixml.hpp>
#include <sstream>
#include <string>

#include "io/indoorgml.hpp"
#include "io/map_export.hpp"
#include "maps/plane_index.hpp"
#include "maps/polygon_triangulation.hpp"

namespace fs = std::filesystem;
namespace cm = conicloc::maps;
namespace ci = conicloc::io;

namespace {

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

const cm::PlaneMap& example() {
  static const cm::PlaneMap map = ci::load_indoorgml(CONICLOC_EXAMPLE_MAP).map;
  return map;
}

double triangulated_area(const cm::PlanarPolygon& polygon) {
  std::vector<Eigen::Vector3d> v(polygon.outer.begin(), polygon.outer.end());
  for (const auto& hole : polygon.holes) v.insert(v.end(), hole.begin(), hole.end());
  double area = 0.0;
  for (const auto& t : cm::triangulate(polygon)) {
    const auto& a = v[static_cast<std::size_t>(t[0])];
    const auto& b = v[static_cast<std::size_t>(t[1])];
    const auto& c = v[static_cast<std::size_t>(t[2])];
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

}  // namespace

TEST(ExampleBuilding, CommittedFileIsWhatTheScriptGenerates) {
  const fs::path example(CONICLOC_EXAMPLE_MAP);
  const fs::path script =
      example.parent_path().parent_path() / "scripts" / "make_example_building.py";
  ASSERT_TRUE(fs::exists(example));
  ASSERT_TRUE(fs::exists(script));
  if (std::system("python3 -c 'pass' > /dev/null 2>&1") != 0) GTEST_SKIP() << "no python3";
  const fs::path generated = fs::temp_directory_path() /
                             ("conicloc_example_building_" + std::to_string(::getpid()) + ".gml");
  const std::string command =
      "python3 '" + script.string() + "' '" + generated.string() + "' > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  EXPECT_EQ(read_all(generated), read_all(example))
      << "examples/example_building.gml is out of date: re-run scripts/make_example_building.py";
  fs::remove(generated);
}

TEST(ExampleBuilding, LoadsWithTheDesignedLayout) {
  const auto& map = example();
  ASSERT_EQ(map.cells.size(), 10u);  // floor 0: A, B, C, D, corridor; floor 1: office, C, D,
                                     // corridor; the staircase
  int general = 0, transition = 0;
  for (const auto& cell : map.cells) {
    general += cell.class_name == "GeneralSpace";
    transition += cell.class_name == "TransitionSpace";
    EXPECT_FALSE(cell.polygons.empty()) << cell.id;
  }
  EXPECT_EQ(general, 7);
  EXPECT_EQ(transition, 3);
  ASSERT_EQ(map.storeys.size(), 2u);
  EXPECT_NEAR(map.storeys[0].floor_z, 0.0, 1e-9);
  EXPECT_NEAR(map.storeys[1].floor_z, 3.2, 1e-9);
  EXPECT_NEAR((map.bounds.min() - Eigen::Vector3d(0, 0, 0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((map.bounds.max() - Eigen::Vector3d(18, 10, 6.2)).norm(), 0.0, 1e-9);
  EXPECT_EQ(map.navigation.nodes.size(), 10u);
  ASSERT_EQ(map.navigation.edges.size(), 10u);
  for (const auto& edge : map.navigation.edges) EXPECT_TRUE(edge.through_door) << edge.id;

  int holes = 0, slanted_walls = 0, slopes = 0;
  for (const auto& p : map.polygons) {
    EXPECT_GE(p.outer.size(), 3u) << p.source_id;
    holes += static_cast<int>(p.holes.size());
    // The east facade: 30 degrees to the y axis, so its normal is 30 degrees off the x axis.
    if (std::abs(std::abs(p.plane.normal.x()) - std::cos(M_PI / 6)) < 1e-6) ++slanted_walls;
    if (p.kind == cm::SurfaceKind::Slope) ++slopes;
  }
  EXPECT_EQ(holes, 6);          // the windows
  EXPECT_GE(slanted_walls, 6);  // rooms C and D and the corridor, on both storeys
  EXPECT_EQ(slopes, 2);         // the stair flight and the sloped roof of room D on floor 1
}

TEST(ExampleBuilding, EveryPolygonTriangulatesToItsArea) {
  for (const auto& p : example().polygons) {
    EXPECT_NEAR(triangulated_area(p), p.area, 1e-9 * std::max(1.0, p.area)) << p.source_id;
  }
}

TEST(ExampleBuilding, IndexAgreesWithBruteForceInsideTheBuilding) {
  const auto& map = example();
  const cm::PlaneIndex index(map);
  for (double x = 0.5; x < 18.0; x += 1.5) {
    for (double y = 0.5; y < 10.0; y += 1.5) {
      for (const double z : {1.5, 4.7}) {
        const Eigen::Vector3d p(x, y, z);
        std::vector<int> expected;
        for (std::size_t i = 0; i < map.polygons.size(); ++i) {
          if ((cm::closest_point(map.polygons[i], p) - p).norm() <= 4.0) {
            expected.push_back(static_cast<int>(i));
          }
        }
        EXPECT_EQ(index.within(p, 4.0), expected) << p.transpose();
      }
    }
  }
}

TEST(ExampleBuilding, FloorPlanShowsBothStoreysAllDoorsAndWindows) {
  const std::string svg = ci::render_floor_plan_svg(example());
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_string(svg.c_str()));
  int storeys = 0, doors = 0, window_lines = 0;
  for (const auto& g : doc.child("svg").children("g")) {
    if (std::string(g.attribute("class").value()) != "storey") continue;
    ++storeys;
    for (const auto& d : g.find_child_by_attribute("g", "class", "doors").children()) {
      doors += std::string(d.name()) == "line" || std::string(d.name()) == "circle";
    }
    for (const auto& w : g.find_child_by_attribute("g", "class", "windows").children("line")) {
      (void)w;
      ++window_lines;
    }
  }
  EXPECT_EQ(storeys, 2);
  EXPECT_EQ(doors, 10);            // one per Transition, each on its own storey
  EXPECT_EQ(window_lines, 2 * 6);  // glazing drawn as two lines; all windows are cut at 1 m
}

TEST(ExampleBuilding, ObjMeshHasEveryTriangleAndOneObjectPerCell) {
  std::ostringstream out;
  const auto stats = ci::write_obj(example(), out);
  EXPECT_EQ(stats.objects, 10);
  EXPECT_EQ(stats.normals, static_cast<int>(example().polygons.size()));
  std::size_t triangles = 0;
  for (const auto& p : example().polygons) triangles += cm::triangulate(p).size();
  EXPECT_EQ(stats.faces, static_cast<int>(triangles));
}
