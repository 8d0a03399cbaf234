#pragma once
// RawBuilding (as read from an IndoorGML file) -> PlaneMap: the whole map-building pipeline.
//   frame (CRS, unit scale, origin) -> the topographic layer's cells -> cell surfaces (fit,
//   orient) -> door openings -> coplanar merge -> cells (bounds, footprint, representative
//   point) -> navigation -> floors of floorless cells -> storeys.

#include <map>
#include <string>
#include <vector>

#include "maps/plane_map.hpp"
#include "maps/raw_building.hpp"

namespace conicloc::maps {

struct BuildOptions {
  double storey_height_m = 3.0;  ///< wall height of 2D-only models (metres, after unit_scale)
  double unit_scale = 1.0;       ///< file units -> metres for metric CRSs (0.001 for millimetres)
  bool close_doors = false;      ///< keep door surfaces as walls instead of openings
};

struct BuildReport {
  std::map<std::string, int> cells_by_class;
  std::map<std::string, int> polygons_dropped;  ///< reason -> count
  int cells_left_out = 0;  ///< cells of other space layers (coverage, zones) drawn over the rooms
  std::vector<std::string>
      space_layer_notes;  ///< per layer left out (which, how many, why), or why none was
  int planes_after_merge = 0;
  int faces_merged = 0;
  int two_sided_faces = 0;
  int partial_overlaps = 0;
  int doors = 0;  ///< boundaries classified as doors between navigable cells
  int door_holes_cut = 0;
  int door_surfaces_removed = 0;
  int shells_flipped = 0;  ///< shells written with outward normals, turned inward
  int open_shells = 0;
  double max_flatness_m = 0.0;  ///< worst distance of an input vertex from its fitted plane
  int nonplanar_polygons = 0;   ///< flatness above 1 cm
  bool extruded_2d = false;
  std::string crs_handling;
  std::vector<std::string> warnings;
};

struct BuildResult {
  PlaneMap map;
  BuildReport report;
};

BuildResult build_plane_map(const RawBuilding& raw, const BuildOptions& options = {});

}  // namespace conicloc::maps
