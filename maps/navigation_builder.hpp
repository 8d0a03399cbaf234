#pragma once
// The navigation graph of a PlaneMap: a node per cell (its IndoorGML State when there is one),
// an edge per Transition, or per boundary shared by two cells when the file has no dual graph.

#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "maps/map_frame.hpp"
#include "maps/plane_map.hpp"
#include "maps/raw_building.hpp"

namespace conicloc::maps {

/// What the builder knows about a boundary: its centre (map frame) and whether it is a door.
struct BoundaryInfo {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  bool door = false;
};

/// Precondition: `map.cells` are filled (ids, representative points) in the order of the raw
/// cells that have geometry; `cell_of_raw[i]` is the map cell of raw cell i or -1.
NavigationGraph build_navigation_graph(const RawBuilding& raw, const std::vector<int>& cell_of_raw,
                                       const PlaneMap& map, const MapFrame& frame,
                                       const std::map<std::string, BoundaryInfo>& boundaries,
                                       std::vector<std::string>& warnings);

}  // namespace conicloc::maps
