#pragma once
// Fills in what a route needs when a model leaves it out: a cell footprint (the outline of the
// cell's one floor polygon, else its bounding box) and node points inside their cells (States
// without geometry, or placed outside their cell).

#include "maps/plane_map.hpp"

namespace conicloc::sim {

/// A copy of `map` where every cell with fewer than 3 footprint vertices gets one, and every
/// navigation node whose xy lies outside its cell's footprint is moved to a point inside it
/// (the footprint's centroid when inside, else the inside grid point nearest to it), at the
/// cell's floor height.
maps::PlaneMap with_navigation_geometry(const maps::PlaneMap& map);

}  // namespace conicloc::sim
