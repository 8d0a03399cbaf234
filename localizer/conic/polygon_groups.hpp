#pragma once
// The map's polygons in groups that a prediction can leave out whole (DESIGN.md "Leave out what
// a scene does not need"): one group per cell (the polygons that bound a room), one per polygon
// that bounds no cell. Behind the floor, ceiling and walls around the sensor, a whole room of
// another storey or down the corridor is hidden (occlusion_bins.hpp) when its box is: its
// polygons are then never moved into the sensor frame nor tested ring by ring, and the cost of a
// prediction follows what the pose sees, not the size of the building.

#include <Eigen/Geometry>
#include <vector>

#include "localizer/conic/occlusion_bins.hpp"
#include "localizer/conic/pose.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::localizer {

/// A group's box as a sensor sees it, each figure a bound that holds for every point in it.
struct SensorBox {
  double nearest_m = 0.0;            ///< distance from the sensor origin to the box (0 when inside)
  double z_low = 0.0, z_high = 0.0;  ///< height range, sensor frame
  AzimuthSpan span;                  ///< azimuths of its projection onto the sensor's xy plane
  /// Elevation band from the sensor origin, in radians ([-10, 10] when the box holds the origin).
  double elevation_low = -10.0, elevation_high = 10.0;
};

/// Elevation band [lo, hi] (radians, from the sensor origin) that holds every point of the
/// sphere (sensor frame) seen from any apex (0, 0, o) with |o| ≤ max_offset_m; false (lo, hi
/// untouched) when the sphere holds an apex.
bool sphere_elevation_band(const Eigen::Vector3d& centre, double radius, double max_offset_m,
                           double& lo, double& hi);

/// The box `box` (map frame) seen from a sensor at T_map_sensor, its apexes within
/// `max_offset_m` of the origin along z: nearest_m is the distance from the origin less
/// max_offset_m; z_low/z_high are exact over the box's corners; the span and the elevation band
/// are those of the disc / sphere around the box's centre that holds its projection / itself,
/// widened for the apexes.
SensorBox sensor_box(const Eigen::AlignedBox3d& box, const Pose3& T_map_sensor,
                     double max_offset_m);

class PolygonGroups {
 public:
  explicit PolygonGroups(const maps::PlaneMap& map);

  int group_of(int polygon) const { return group_of_[static_cast<std::size_t>(polygon)]; }
  std::size_t size() const { return boxes_.size(); }
  /// The box of the outer-ring vertices of the group's polygons (map frame).
  const Eigen::AlignedBox3d& box(int group) const {
    return boxes_[static_cast<std::size_t>(group)];
  }

 private:
  std::vector<int> group_of_;
  std::vector<Eigen::AlignedBox3d> boxes_;
};

}  // namespace conicloc::localizer
