#pragma once
// Small errors of a surveyed map: the real walls stand a few centimetres off and slightly out of
// plumb from where the model puts them.

#include <random>
#include <vector>

#include "maps/planar_polygon.hpp"

namespace conicloc::sim {

/// Copies `polygons`, moving each wall (SurfaceKind::Wall) by a normal offset ~ N(0, σ) and
/// tilting it about its horizontal axis through the centroid by an angle ~ N(0, σ / height), so
/// the top edge moves by about σ too. Other surfaces are kept. σ = `error_m`; 0 copies unchanged.
std::vector<maps::PlanarPolygon> perturb_walls(const std::vector<maps::PlanarPolygon>& polygons,
                                               double error_m, std::mt19937_64& rng);

}  // namespace conicloc::sim
