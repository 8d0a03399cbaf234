#pragma once
// Navigable cells whose model holds no floor (no walkable ground, walkable_ground.hpp: a shell
// without its bottom). Cell::floor_z, their lowest vertex, is then the foot of a wall, which may
// lie well below where anyone stands; the doors they are entered by say where that is.

#include <string>
#include <vector>

#include "maps/plane_map.hpp"

namespace conicloc::maps {

/// Gives every navigable cell without a floor (cell_has_floor) the median height of its
/// thresholds: for each navigation edge to a navigable cell with a floor, that cell's ground
/// 0.2 m in from the edge's door point (at its node where that is nearer), where it lies within
/// the floorless cell's height range. The cell's representative point and navigation nodes
/// follow (not their edges' lengths: build the graph again for those); a warning names the cell
/// and both heights. A cell without such a threshold keeps its lowest vertex. Returns the
/// number of cells given a floor.
int assign_floors_to_floorless_cells(PlaneMap& map, std::vector<std::string>& warnings);

}  // namespace conicloc::maps
