#pragma once
// The GML surfaces of a prism cell, oriented as scripts/make_example_building.py writes them:
// shell polygons OUTWARD (normal away from the cell's free space), doors as notches in the outer
// ring of every wall they pierce, and a door's own polygon facing from its first cell to its
// second.

#include <string>
#include <vector>

#include "maps/planar_polygon.hpp"
#include "sim/prism_building.hpp"

namespace conicloc::sim {

struct ShellPolygon {
  std::string suffix;  ///< "floor", "ceiling", "wall-3", ...: the gml:id is "<cell id>-<suffix>"
  maps::Ring3 outer;   ///< open ring
  std::vector<maps::Ring3> holes;
};

/// The exterior shell: floor (one polygon per profile segment for a stair), ceiling (both with
/// the pillars as interior rings) and one wall per footprint edge with the notches of `doors`
/// that join this cell on that edge. Precondition: a cell with a floor profile has a rectangular
/// footprint; every door of the cell reaches down to its floor.
std::vector<ShellPolygon> exterior_shell(const PrismCell& cell,
                                         const std::vector<DoorOpening>& doors);

/// One interior shell (a void from floor to ceiling) per pillar, its normals pointing away from
/// the cell's free space, i.e. into the pillar (ISO 19107 orientation of interior shells).
std::vector<std::vector<ShellPolygon>> pillar_shells(const PrismCell& cell);

/// The door's rectangle, its normal pointing from `first` (the door's first cell) into the second.
maps::Ring3 door_ring(const DoorOpening& door, const PrismCell& first);

}  // namespace conicloc::sim
