#pragma once
// Which surfaces of a cell can be stood on: the one rule the localizer's free space and the
// map's floorless cells share (the simulator keeps its own, with its own ray cast).

#include <optional>

#include "maps/plane_map.hpp"

namespace conicloc::maps {

/// Whether map.polygons[polygon] is ground one stands on in `cell`: its normal, facing the cell
/// (a two-sided surface faces its back cell with −n), is within 60° of up — floors, ramps, stair
/// flights modelled as slopes (a 37° flight has n_z = 0.8), never walls or ceilings — and it
/// lies at least 1 m below the cell's top (not the top face of a pillar reaching the ceiling).
bool is_walkable_ground(const PlaneMap& map, int polygon, int cell);

/// Whether some surface of `cell` is walkable ground.
bool cell_has_floor(const PlaneMap& map, int cell);

/// The height at (x, y) of the highest walkable ground of `cell` whose plan outline holds
/// (x, y) and that is not above `z_max`: its plane z = −(n_x x + n_y y + d)/n_z. nullopt where
/// none does.
std::optional<double> ground_height_at(const PlaneMap& map, int cell, double x, double y,
                                       double z_max);

}  // namespace conicloc::maps
