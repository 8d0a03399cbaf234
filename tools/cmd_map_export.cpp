// `conicloc map-export [FILE] --obj OUT.obj --svg OUT.svg`: the map as a 3D mesh and a floor plan.
#include <spdlog/spdlog.h>

#include "io/indoorgml.hpp"
#include "io/map_export.hpp"
#include "tools/commands.hpp"
#include "tools/map_options.hpp"

namespace conicloc::tools {
namespace {

struct MapExportOptions {
  std::string map_path = example_map_path();
  std::string obj_path;
  std::string svg_path;
  io::FloorPlanOptions plan;
  io::MapLoadOptions map_options;
};

void run_map_export(const MapExportOptions& options) {
  if (options.obj_path.empty() && options.svg_path.empty()) {
    spdlog::error("map-export: nothing to do, give --obj OUT.obj and/or --svg OUT.svg");
    throw CLI::RuntimeError(2);
  }
  const auto loaded = load_map(options.map_path, options.map_options);
  const maps::PlaneMap& map = loaded.map;
  spdlog::info("{}: {} polygons, {} cells, {} storeys", options.map_path, map.polygons.size(),
               map.cells.size(), map.storeys.size());
  if (!options.obj_path.empty()) {
    const auto stats = io::write_obj_file(map, options.obj_path);
    spdlog::info("wrote {}: {} vertices, {} triangles, {} objects, {} groups", options.obj_path,
                 stats.vertices, stats.faces, stats.objects, stats.groups);
  }
  if (!options.svg_path.empty()) {
    io::write_floor_plan_svg(map, options.svg_path, options.plan);
    spdlog::info("wrote {}: floor plan of {} storeys, cut {} m above each floor", options.svg_path,
                 std::max<std::size_t>(map.storeys.size(), 1), options.plan.section_height_m);
  }
}

}  // namespace

void add_map_export_command(CLI::App& app) {
  auto options = std::make_shared<MapExportOptions>();
  auto* cmd = app.add_subcommand(
      "map-export", "Export the map as an OBJ mesh and/or an SVG floor plan per storey");
  cmd->add_option("file", options->map_path, "IndoorGML file (default: the example building)")
      ->check(CLI::ExistingFile)
      ->capture_default_str();
  add_map_load_options(cmd, options->map_options);
  cmd->add_option("--obj", options->obj_path, "Write the planes as a Wavefront OBJ mesh (+ .mtl)");
  cmd->add_option("--svg", options->svg_path, "Write an SVG floor plan, one panel per storey");
  cmd->add_option("--cut-height", options->plan.section_height_m,
                  "Floor plan section height above each storey's floor, metres")
      ->capture_default_str();
  cmd->add_option("--px-per-m", options->plan.pixels_per_m,
                  "Floor plan scale in pixels per metre (0: fit to ~900 px wide)")
      ->capture_default_str();
  cmd->add_flag("--no-graph{false}", options->plan.show_navigation,
                "Leave the navigation graph and doors out of the floor plan");
  cmd->add_flag("--no-labels{false}", options->plan.show_labels, "Leave cell names out");
  cmd->callback([options] { run_map_export(*options); });
}

}  // namespace conicloc::tools
