#pragma once
// Which map plane a measured point lies on: the nearest bounded polygon within a gate. The gate
// shrinks over the calibration's rounds as the model improves (coarse poses first, then tight).

#include <Eigen/Core>

#include "maps/plane_index.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::calib {

/// Index of the polygon of `map` nearest to `point_map` (distance to the bounded polygon, holes
/// excluded), or −1 when none is within `gate_m`.
int nearest_polygon(const maps::PlaneMap& map, const maps::PlaneIndex& index,
                    const Eigen::Vector3d& point_map, double gate_m);

}  // namespace conicloc::calib
