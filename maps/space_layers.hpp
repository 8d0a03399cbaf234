#pragma once
// Which cells bound physical space. IndoorGML's multi-layered space model (OGC 14-005r5, 7.2)
// holds beside the topographic layer (rooms and corridors, whose surfaces are walls) layers whose
// cells are sensor coverage, logical zones or tagged areas drawn over the same rooms (SpaceLayer
// class SENSOR, LOGICAL, TAGS). Their surfaces are no walls: taken as walls they put planes
// across the rooms that no sensor sees, and a route through the rooms crosses them.
//
// The topographic layer is the one declared TOPOGRAPHIC, else the one whose transitions pass
// through the most cell boundaries (its doors), else the first listed. A cell whose state lies in
// another layer is left out when that layer is declared SENSOR, LOGICAL or TAGS, or, declared
// nothing, when more than half of its footprint lies inside the topographic layer's cells at
// heights they share (cells of one layer do not overlap: a cell inside another layer's rooms is
// a zone over them, not a room). A layer of rooms beside the topographic one is kept, and so are
// non-navigable cells (obstacles: columns, shafts) in any layer.

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
  std::vector<std::string> notes;  ///< per layer left out: which, how many cells, and why
};

/// `extents` per raw cell (the same order). Leaves nothing out when the cells' states lie in
/// fewer than two layers.
LayerSelection select_topographic_cells(const RawBuilding& raw,
                                        const std::vector<CellExtent>& extents);

/// True when the file's cells lie in more than one space layer (only then are extents needed).
bool cells_in_several_layers(const RawBuilding& raw);

}  // namespace conicloc::maps
