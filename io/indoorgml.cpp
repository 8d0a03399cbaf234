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
  static_cast<maps::BuildReport&>(report) = std::move(built.report);
  report.version = raw.version;
  report.polygons_read = raw.polygons_read;
  report.states = static_cast<int>(raw.states.size());
  report.transitions = static_cast<int>(raw.transitions.size());
  report.boundaries = static_cast<int>(raw.boundaries.size());
  report.file_bytes = source.size_bytes();
  return loaded;
}

}  // namespace conicloc::io
