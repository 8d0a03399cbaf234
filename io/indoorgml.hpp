#pragma once
// load_indoorgml(): an IndoorGML file (1.0.1, 1.0.3 or 2.0) as a PlaneMap plus a load report.

#include <map>
#include <string>
#include <vector>

#include "maps/build_plane_map.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::io {

struct MapLoadOptions {
  double storey_height_m = 3.0;  ///< wall height for 2D-only models, metres
  double unit_scale = 1.0;       ///< file units -> metres (metric CRSs)
  bool close_doors = false;      ///< keep doors between navigable cells as walls
};

/// What the map builder reported, plus what only the file tells.
struct MapLoadReport : maps::BuildReport {
  std::string version;  ///< "1.0.1", "1.0.3", "2.0"
  int polygons_read = 0;  ///< cell surface polygons in the file
  int states = 0;
  int transitions = 0;
  int boundaries = 0;
  std::size_t file_bytes = 0;
};

struct LoadedMap {
  conicloc::maps::PlaneMap map;
  MapLoadReport report;
};

/// Throws InputError (file, line, element and gml:id) for malformed XML, a document that is not
/// IndoorGML, broken xlinks, NaN or missing coordinates, and a model without cell geometry.
LoadedMap load_indoorgml(const std::string& path, const MapLoadOptions& options = {});

}  // namespace conicloc::io
