#pragma once
// The walkable ground of a building for the simulated carrier: floors, ramps and stair flights
// (surfaces facing up). The trajectory is draped on it so the sensor keeps its height above the
// floor on a stair, found with the simulator's own vertical ray cast (not the localizer's code).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "maps/planar_polygon.hpp"
#include "sim/polygon_bvh.hpp"

namespace conicloc::sim {

class FloorSurface {
 public:
  /// Keeps the polygons that can be walked on: upward normal within 60° of vertical (the map's
  /// normals face the free space), and two-sided horizontal slabs.
  explicit FloorSurface(const std::vector<maps::PlanarPolygon>& polygons);

  /// Height of the highest walkable surface under (x, y) of `near_point`, searched from
  /// `search_up_m` above its z down to `search_down_m` below it; nullopt when there is none.
  /// The default reach up is 2 m: a route's nominal floor is interpolated between door heights,
  /// so inside a stairwell the flight can rise well above it (1.6 m at the example's stair node;
  /// with 1 m the path fell through the flight to the nominal height), while the next storey's
  /// floor is at least a storey height (≥ 2.5 m) away.
  std::optional<double> height_under(const Eigen::Vector3d& near_point, double search_up_m = 2.0,
                                     double search_down_m = 1.5) const;

  std::size_t surface_count() const { return bvh_.polygons().size(); }

 private:
  PolygonBvh bvh_;
};

}  // namespace conicloc::sim
