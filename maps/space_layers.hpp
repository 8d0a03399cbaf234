#pragma once
// Which cells bound physical space. IndoorGML's multi-layered space model (OGC 14-005r5, 7.2)
// holds beside the topographic layer (rooms and corridors, whose surfaces are walls) layers whose
// cells are sensor coverage, logical zones or tagged areas drawn over the same rooms (SpaceLayer
// class SENSOR, LOGICAL, TAGS; in 2.0 a ThematicLayer of theme Virtual). Their surfaces are no
// walls: taken as walls they put planes across the rooms that no sensor sees, and a route
// through the rooms crosses them.
//
// The topographic layer is the one declared TOPOGRAPHIC (2.0: Physical), else the one whose
// transitions pass through the most cell boundaries (its doors), else the first listed. A cell of
// another layer is left out when that layer is declared SENSOR, LOGICAL, TAGS or Virtual, or,
// declared nothing (or UNKNOWN), when most of its cells' area lies in the topographic layer's
// rooms and one of its cells crosses a wall between two rooms side by side (cells of one layer do
// not overlap: a cell across a wall is a zone, not a room). A layer of rooms beside the
// topographic one is kept, so are obstacles inside a room and non-navigable cells (columns,
// shafts) in any layer, and so is everything when no layer is declared and their doors tie.

#include <string>
#include <vector>

#include "maps/planar_polygon.hpp"
#include "maps/raw_building.hpp"

namespace conicloc::maps {

/// A cell's extent in the map frame: its xy outline and the heights it spans.
struct CellExtent {
  Ring2 footprint;  ///< empty: no geometry
  double floor_z = 0.0;
  double ceiling_z = 0.0;
};

struct LayerSelection {
  std::vector<bool> left_out;      ///< per raw cell
  std::vector<std::string> notes;  ///< per layer left out (which, how many cells, why), or why
                                   ///< none could be
};

/// `extents` per raw cell (the same order). Leaves nothing out when the cells' states lie in
/// fewer than two layers.
LayerSelection select_topographic_cells(const RawBuilding& raw,
                                        const std::vector<CellExtent>& extents);

/// True when the file's cells lie in more than one space layer (only then are extents needed).
bool cells_in_several_layers(const RawBuilding& raw);

}  // namespace conicloc::maps
