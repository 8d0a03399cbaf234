#include "io/indoorgml.hpp"

#include "io/indoorgml_structure.hpp"
#include "io/xml_source.hpp"
#include "maps/build_plane_map.hpp"

namespace conicloc::io {

LoadedMap load_indoorgml(const std::string& path, const MapLoadOptions& options) {
  const XmlSource source(path);
  const maps::RawBuilding raw = read_indoorgml_structure(source);

  maps::BuildOptions build_options;
  build_options.storey_height_m = options.storey_height_m;
  build_options.unit_scale = options.unit_scale;
  build_options.close_doors = options.close_doors;
  maps::BuildResult built = maps::build_plane_map(raw, build_options);

  LoadedMap loaded;
  loaded.map = std::move(built.map);
  MapLoadReport& report = loaded.report;
  const maps::BuildReport& b = built.report;
  report.version = raw.version;
  report.cells_by_class = b.cells_by_class;
  report.polygons_read = raw.polygons_read;
  report.polygons_dropped = b.polygons_dropped;
  report.planes_after_merge = b.planes_after_merge;
  report.warnings = b.warnings;
  report.crs_handling = b.crs_handling;
  report.states = static_cast<int>(raw.states.size());
  report.transitions = static_cast<int>(raw.transitions.size());
  report.boundaries = static_cast<int>(raw.boundaries.size());
  report.doors = b.doors;
  report.faces_merged = b.faces_merged;
  report.two_sided_faces = b.two_sided_faces;
  report.door_holes_cut = b.door_holes_cut;
  report.door_surfaces_removed = b.door_surfaces_removed;
  report.shells_flipped = b.shells_flipped;
  report.max_flatness_m = b.max_flatness_m;
  report.nonplanar_polygons = b.nonplanar_polygons;
  report.extruded_2d = b.extruded_2d;
  report.file_bytes = source.size_bytes();
  return loaded;
}

}  // namespace conicloc::io
