#pragma once
// Clutter the map lacks: furniture boxes standing on the floors and people walking in the rooms.

#include <random>
#include <vector>

#include "maps/plane_map.hpp"
#include "sim/moving_person.hpp"
#include "sim/world.hpp"

namespace conicloc::sim {

struct ClutterConfig {
  int level = 1;             ///< 0 none, 1 light, 2 medium, 3 heavy
  double clearance_m = 0.6;  ///< free space kept around the sensor's path
};

struct Clutter {
  std::vector<maps::PlanarPolygon> polygons;  ///< box faces (four sides and the top)
  std::vector<SurfaceMaterial> materials;     ///< one per polygon
  std::vector<MovingPerson> people;
  int boxes = 0;
};

/// Per navigable cell: about level × area / 25 m² boxes (0.4–1.6 m wide, 0.4–0.9 m deep,
/// 0.4–1.8 m high, any yaw) fully inside the footprint, and level × area / 60 m² people walking
/// straight lines inside it. Nothing is placed within `clearance_m` (plus its own size) of `path`
/// (map-frame points along the sensor's route, at sensor height), so the sensor never drives into
/// clutter. People walk with an unchanged clearance test against the path's points.
Clutter make_clutter(const maps::PlaneMap& map, const std::vector<Eigen::Vector3d>& path,
                     const ClutterConfig& config, std::mt19937_64& rng);

}  // namespace conicloc::sim
