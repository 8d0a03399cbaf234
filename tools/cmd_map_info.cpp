// conicloc map-info [FILE] [--json]: what the loader made of an IndoorGML building model.
#include <CLI/CLI.hpp>
#include <iomanip>
#include <iostream>
#include <memory>

#include "io/indoorgml.hpp"
#include "tools/commands.hpp"
#include "tools/json_writer.hpp"
#include "tools/map_options.hpp"

namespace conicloc::tools {
namespace {

struct MapInfoArgs {
  std::string file = example_map_path();
  bool json = false;
  io::MapLoadOptions options;
};

int total_cells(const io::MapLoadReport& report) {
  int total = 0;
  for (const auto& [name, count] : report.cells_by_class) total += count;
  return total;
}

void write_vector(JsonWriter& json, const Eigen::Vector3d& v) {
  json.array({v.x(), v.y(), v.z()});
}

void print_json(const io::LoadedMap& loaded, std::ostream& out) {
  const auto& map = loaded.map;
  const auto& report = loaded.report;
  JsonWriter json(out);
  json.begin_object();
  json.key("version").value(report.version);
  json.key("crs").value(map.crs);
  json.key("crs_handling").value(report.crs_handling);
  json.key("cells").begin_object();
  for (const auto& [name, count] : report.cells_by_class) json.key(name).value(count);
  json.end_object();
  json.key("cells_left_out").value(report.cells_left_out);
  json.key("polygons").begin_object();
  json.key("read").value(report.polygons_read);
  json.key("dropped").begin_object();
  for (const auto& [reason, count] : report.polygons_dropped) json.key(reason).value(count);
  json.end_object();
  json.key("max_flatness_m").value(report.max_flatness_m);
  json.end_object();
  json.key("planes").value(report.planes_after_merge);
  json.key("merged_faces").value(report.faces_merged);
  json.key("two_sided_faces").value(report.two_sided_faces);
  json.key("doors").value(report.doors);
  json.key("storeys").begin_array();
  for (const auto& storey : map.storeys) {
    json.begin_object();
    json.key("name").value(storey.name);
    json.key("floor_z").value(storey.floor_z);
    json.key("ceiling_z").value(storey.ceiling_z);
    json.end_object();
  }
  json.end_array();
  json.key("origin");
  write_vector(json, map.origin);
  json.key("bbox_min");
  write_vector(json, map.bounds.min());
  json.key("bbox_max");
  write_vector(json, map.bounds.max());
  json.key("nav_nodes").value(static_cast<int>(map.navigation.nodes.size()));
  json.key("nav_edges").value(static_cast<int>(map.navigation.edges.size()));
  json.key("warnings").array_of(report.warnings);
  json.end_object();
  out << '\n';
}

void print_text(const std::string& file, const io::LoadedMap& loaded, std::ostream& out) {
  const auto& map = loaded.map;
  const auto& report = loaded.report;
  auto vec = [](const Eigen::Vector3d& v) {
    std::ostringstream s;
    s << std::fixed << std::setprecision(3) << "(" << v.x() << ", " << v.y() << ", " << v.z()
      << ")";
    return s.str();
  };
  out << "file:            " << file << "\n";
  out << "IndoorGML:       " << report.version << "\n";
  out << "CRS handling:    " << report.crs_handling << "\n";
  out << "origin:          " << vec(map.origin) << " (file metres of the map frame's zero)\n";
  out << "cells:           " << total_cells(report) << "\n";
  for (const auto& [name, count] : report.cells_by_class)
    out << "  " << name << ": " << count << "\n";
  if (report.cells_left_out > 0)
    out << "  left out (other space layers): " << report.cells_left_out << "\n";
  out << "polygons read:   " << report.polygons_read << " (max deviation from plane "
      << std::setprecision(3) << report.max_flatness_m << " m, " << report.nonplanar_polygons
      << " above 1 cm)\n";
  int dropped = 0;
  for (const auto& [reason, count] : report.polygons_dropped) dropped += count;
  out << "polygons dropped: " << dropped << "\n";
  for (const auto& [reason, count] : report.polygons_dropped)
    out << "  " << reason << ": " << count << "\n";
  out << "planes:          " << report.planes_after_merge << " after merging ("
      << report.faces_merged << " coplanar faces merged, " << report.two_sided_faces
      << " two-sided walls, " << report.shells_flipped << " shells turned inward)\n";
  out << "doors:           " << report.doors << " (" << report.door_holes_cut << " openings cut, "
      << report.door_surfaces_removed << " door faces removed)\n";
  out << "storeys:         " << map.storeys.size() << "\n";
  for (const auto& storey : map.storeys) {
    out << "  " << storey.name << ": floor " << std::fixed << std::setprecision(2) << storey.floor_z
        << " m, ceiling " << storey.ceiling_z << " m\n";
  }
  out << "bounding box:    " << vec(map.bounds.min()) << " .. " << vec(map.bounds.max())
      << " m (map frame)\n";
  out << "navigation:      " << map.navigation.nodes.size() << " nodes, "
      << map.navigation.edges.size() << " edges\n";
  for (const auto& warning : report.warnings) out << "warning: " << warning << "\n";
}

}  // namespace

void add_map_info_command(CLI::App& app) {
  auto args = std::make_shared<MapInfoArgs>();
  CLI::App* command = app.add_subcommand("map-info", "Summarise an IndoorGML building model");
  command->add_option("file", args->file, "IndoorGML file (default: the shipped example building)");
  command->add_flag("--json", args->json, "Print one JSON object");
  add_map_load_options(command, args->options);
  command->callback([args] {
    const io::LoadedMap loaded = io::load_indoorgml(args->file, args->options);
    if (args->json) {
      print_json(loaded, std::cout);
    } else {
      print_text(args->file, loaded, std::cout);
    }
  });
}

}  // namespace conicloc::tools
