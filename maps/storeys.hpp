#pragma once
// Storeys from cell floor heights: cells whose floors lie within a step of each other share one.

#include <vector>

#include "maps/plane_map.hpp"

namespace conicloc::maps {

/// Clusters cells by floor_z (sorted; a new storey where consecutive floors differ by more than
/// `min_step_m`), fills PlaneMap::storeys (sorted by floor_z) and Cell::storey, and sets
/// PlanarPolygon::storey from each polygon's cell. A storey's floor_z is the lowest floor of its
/// cells, its ceiling_z the median of their ceilings (stairwells reach higher).
void assign_storeys(PlaneMap& map, double min_step_m = 1.2);

}  // namespace conicloc::maps
