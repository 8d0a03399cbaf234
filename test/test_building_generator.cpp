// Generated buildings (sim/building_generator): every kind and seed loads as the layout promises
// (doors, a connected navigation graph, storeys, pillars, sloped and non-Manhattan planes), the
// text repeats per seed, bad kinds and specs are named, and `conicloc simulate` runs in them.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <queue>
#include <stdexcept>

#include "io/indoorgml.hpp"
#include "sim/building_generator.hpp"
#include "test/cli_run.hpp"
#include "test/temp_path.hpp"

namespace {

namespace fs = std::filesystem;
using conicloc::maps::PlaneMap;
using conicloc::maps::SurfaceKind;
using conicloc::sim::generate_building_gml;
using conicloc::sim::generated_building_kinds;

conicloc::io::LoadedMap load_generated(const std::string& kind, std::uint64_t seed,
                                       const conicloc::sim::BuildingScale& scale = {}) {
  const fs::path path = conicloc::test::unique_temp_path(kind + std::to_string(seed) + ".gml");
  std::ofstream(path) << generate_building_gml(kind, seed, scale);
  auto loaded = conicloc::io::load_indoorgml(path.string());
  fs::remove(path);
  return loaded;
}

// Navigable cells no walk along the navigation graph from the first navigable one reaches.
int unreachable_navigable_cells(const PlaneMap& map) {
  const auto& graph = map.navigation;
  std::vector<std::vector<int>> next(graph.nodes.size());
  for (const auto& edge : graph.edges) {
    next[edge.from].push_back(edge.to);
    next[edge.to].push_back(edge.from);
  }
  std::vector<bool> seen(graph.nodes.size(), false);
  std::queue<int> open;
  open.push(0);
  seen[0] = true;
  while (!open.empty()) {
    const int node = open.front();
    open.pop();
    for (const int other : next[node]) {
      if (!seen[other]) seen[other] = true, open.push(other);
    }
  }
  int unreachable = 0;
  for (std::size_t n = 0; n < graph.nodes.size(); ++n) {
    if (!seen[n] && map.cells[graph.nodes[n].cell].navigable) ++unreachable;
  }
  return unreachable;
}

bool has_slope(const PlaneMap& map) {
  for (const auto& polygon : map.polygons) {
    if (polygon.kind == SurfaceKind::Slope) return true;
  }
  return false;
}

bool has_non_manhattan_wall(const PlaneMap& map) {
  for (const auto& polygon : map.polygons) {
    const auto& n = polygon.plane.normal;
    if (polygon.kind == SurfaceKind::Wall && std::abs(n.x()) > 0.1 && std::abs(n.y()) > 0.1)
      return true;
  }
  return false;
}

// Pillar sides: walls of the hall away from its outline. Each must face away from the opposite
// side of its pillar (into the hall, where the sensor sees it). Returns their count.
int pillar_faces_facing_out(const PlaneMap& map) {
  int hall = -1;
  for (std::size_t c = 0; c < map.cells.size(); ++c) {
    if (map.cells[c].id == "Hall") hall = static_cast<int>(c);
  }
  const auto& box = map.cells.at(hall).bounds;
  std::vector<const conicloc::maps::PlanarPolygon*> sides;
  for (const auto& polygon : map.polygons) {
    const Eigen::Vector3d c = polygon.centroid;
    if (polygon.cell == hall && polygon.kind == SurfaceKind::Wall && polygon.radius < 3.0 &&
        c.x() > box.min().x() + 1.0 && c.x() < box.max().x() - 1.0 && c.y() > box.min().y() + 1.0 &&
        c.y() < box.max().y() - 1.0) {
      sides.push_back(&polygon);
    }
  }
  int facing_out = 0;
  for (const auto* side : sides) {
    for (const auto* other : sides) {
      const double apart = (other->centroid - side->centroid).norm();
      if (other->plane.normal.dot(side->plane.normal) < -0.99 && apart < 1.0 &&
          (other->centroid - side->centroid).dot(side->plane.normal) < 0.0) {
        ++facing_out;
        break;
      }
    }
  }
  EXPECT_EQ(facing_out, static_cast<int>(sides.size())) << "pillar sides facing into a pillar";
  return facing_out;
}

TEST(BuildingGenerator, KindsInFixedOrder) {
  EXPECT_EQ(generated_building_kinds(),
            (std::vector<std::string>{"corridor", "wings", "hall", "storeys"}));
}

TEST(BuildingGenerator, EveryKindLoadsAsPromised) {
  for (const auto& kind : generated_building_kinds()) {
    for (const std::uint64_t seed : {1u, 2u, 3u}) {
      SCOPED_TRACE(kind + " seed " + std::to_string(seed));
      const auto loaded = load_generated(kind, seed);
      const PlaneMap& map = loaded.map;
      EXPECT_EQ(loaded.report.version, "1.0.3");
      EXPECT_TRUE(loaded.report.polygons_dropped.empty());
      EXPECT_EQ(loaded.report.nonplanar_polygons, 0);
      EXPECT_EQ(loaded.report.open_shells, 0);
      EXPECT_GT(loaded.report.doors, 0);
      EXPECT_EQ(loaded.report.doors, loaded.report.transitions);  // every door is a Transition
      EXPECT_EQ(map.navigation.nodes.size(), map.cells.size());
      EXPECT_EQ(unreachable_navigable_cells(map), 0);
      EXPECT_TRUE(loaded.report.warnings.empty()) << loaded.report.warnings.front();

      int stairs = 0;
      for (const auto& cell : map.cells) stairs += cell.id.rfind("Stair", 0) == 0 ? 1 : 0;
      if (kind == "storeys") {
        EXPECT_GE(map.storeys.size(), 2u);
        EXPECT_LE(map.storeys.size(), 4u);
        EXPECT_EQ(static_cast<int>(map.storeys.size()), stairs + 1);
      } else {
        EXPECT_EQ(map.storeys.size(), 1u);
      }
      // Sloped ceilings (corridor, wings) and stair flights (storeys) are Slope planes.
      EXPECT_EQ(has_slope(map), kind != "hall");
      if (kind == "corridor") {
        EXPECT_TRUE(has_non_manhattan_wall(map));
      }
      if (kind == "hall") {
        EXPECT_GE(pillar_faces_facing_out(map), 16);  // 2 x 2 pillars at least
      }
    }
  }
}

// A scaled storeys building: the storey count asked for, the floor plate (the same whatever the
// count) repeated along the corridor, rooms in proportion, every cell reachable, one stair per
// storey pair, the storeys as far apart as in the seed's own building.
TEST(BuildingGenerator, ScaledStoreysHaveTheAskedStoreysAndFloorPlates) {
  for (const std::uint64_t seed : {2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const auto drawn = load_generated("storeys", seed);
    const double rise = drawn.map.storeys[1].floor_z - drawn.map.storeys[0].floor_z;
    const auto one = load_generated("storeys", seed, {1, 1});
    const int cells_per_plate = static_cast<int>(one.map.cells.size()) - 1;  // rooms
    for (const auto& [storeys, plates] : {std::pair{1, 3}, {6, 1}, {6, 3}}) {
      SCOPED_TRACE(std::to_string(storeys) + "x" + std::to_string(plates));
      const auto scaled = load_generated("storeys", seed, {storeys, plates});
      const PlaneMap& map = scaled.map;
      EXPECT_TRUE(scaled.report.warnings.empty());
      EXPECT_EQ(scaled.report.open_shells, 0);
      EXPECT_EQ(static_cast<int>(map.storeys.size()), storeys);
      EXPECT_EQ(static_cast<int>(map.cells.size()),
                storeys * (1 + plates * cells_per_plate) + (storeys - 1));
      EXPECT_EQ(unreachable_navigable_cells(map), 0);
      EXPECT_NEAR(map.bounds.sizes().x(), plates * one.map.bounds.sizes().x(), 1e-6);
      EXPECT_NEAR(map.storeys.back().floor_z - map.storeys.front().floor_z, (storeys - 1) * rise,
                  1e-6);
    }
  }
  EXPECT_THROW(generate_building_gml("hall", 1, {2, 1}), std::invalid_argument);
  EXPECT_THROW(generate_building_gml("storeys", 1, {2, 0}), std::invalid_argument);
  EXPECT_THROW(generate_building_gml("storeys", 1, {conicloc::sim::kMaxStoreys + 1, 1}),
               std::invalid_argument);
}

TEST(BuildingGenerator, SameSeedSameTextOtherSeedOtherText) {
  for (const auto& kind : generated_building_kinds()) {
    const std::string text = generate_building_gml(kind, 7);
    EXPECT_EQ(text, generate_building_gml(kind, 7)) << kind;
    EXPECT_NE(text, generate_building_gml(kind, 8)) << kind;
  }
}

TEST(BuildingGenerator, UnknownKindNamesTheKnownOnes) {
  try {
    generate_building_gml("castle", 1);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("castle"), std::string::npos) << message;
    EXPECT_NE(message.find("corridor, wings, hall, storeys"), std::string::npos) << message;
  }
}

TEST(BuildingGenerator, ParsesSpecs) {
  using conicloc::sim::parse_generated_building_spec;
  const auto spec = parse_generated_building_spec("generated:corridor:3");
  ASSERT_TRUE(spec.has_value());
  EXPECT_EQ(spec->kind, "corridor");
  EXPECT_EQ(spec->seed, 3u);
  EXPECT_TRUE(spec->scale.is_default());
  const auto scaled = parse_generated_building_spec("generated:storeys:1:10x4");
  ASSERT_TRUE(scaled.has_value());
  EXPECT_EQ(scaled->seed, 1u);
  EXPECT_EQ(scaled->scale.storeys, 10);
  EXPECT_EQ(scaled->scale.plate_tiles, 4);
  const auto drawn = parse_generated_building_spec("generated:storeys:1:0x2");  // storeys drawn
  ASSERT_TRUE(drawn.has_value());
  EXPECT_EQ(drawn->scale.storeys, 0);
  EXPECT_EQ(drawn->scale.plate_tiles, 2);
  EXPECT_FALSE(parse_generated_building_spec("examples/example_building.gml").has_value());
  const std::pair<std::string, std::string> bad[] = {
      {"generated:corridor", "generated:KIND:SEED"},
      {"generated:corridor:x", "seed \"x\""},
      {"generated:corridor:-1", "seed \"-1\""},
      {"generated:corridor:", "seed \"\""},
      {"generated:castle:1", "unknown generated building kind \"castle\""},
      {"generated:storeys:1:10", "scale \"10\""},
      {"generated:storeys:1:2x0", "scale \"2x0\""},
      {"generated:storeys:1:2x", "scale \"2x\""},
      {"generated:corridor:1:2x2", "a generated corridor building has no scale"}};
  for (const auto& [text, expected] : bad) {
    try {
      parse_generated_building_spec(text);
      ADD_FAILURE() << text << ": no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  }
}

TEST(BuildingGenerator, SimulateRunsInEveryKind) {
  const fs::path dir = conicloc::test::unique_temp_path("generated_buildings");
  fs::create_directories(dir);
  const fs::path log = dir / "log.txt";
  using conicloc::test::run_conicloc;
  using conicloc::test::slurp;
  for (const auto& kind : generated_building_kinds()) {
    const std::string map = (dir / (kind + ".gml")).string();
    ASSERT_EQ(run_conicloc("generate-building --kind " + kind + " --seed 5 --out " + map, log), 0)
        << slurp(log);
    EXPECT_EQ(slurp(map), generate_building_gml(kind, 5));
    ASSERT_EQ(
        run_conicloc("simulate --map " + map + " --duration 3 --out " +
                         (dir / "run.pcap").string() + " --truth " + (dir / "truth.tum").string(),
                     log),
        0)
        << kind << ": " << slurp(log);
  }
  EXPECT_NE(run_conicloc("generate-building --kind castle --out " + (dir / "x.gml").string(), log),
            0);
  fs::remove_all(dir);
}

}  // namespace
