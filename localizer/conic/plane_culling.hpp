#pragma once
// Which map polygons can matter for a pose, or for a region of poses (a particle cloud's bounding
// box) — DESIGN.md "Leave out what a scene does not need". A polygon is left out when it is
//  - out of range: farther than the sensor's maximum range from every sensor position
//  (maps::PlaneIndex, exact);
//  - facing away: every sensor position lies behind its plane by more than a margin (the normal
//    points into the free space the surface faces); never for two-sided polygons (merged faces
//    that bound free space on both sides);
//  - outside the vertical field of view: entirely above the highest ring's cone or below the
//    lowest one for every position, with a tilt allowance for roll and pitch.

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "localizer/conic/pose.hpp"
#include "maps/plane_index.hpp"
#include "maps/plane_map.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::localizer {

struct CullConfig {
  bool cull_back_faces = true;  ///< two-sided polygons (PlanarPolygon::two_sided) are kept
  double back_face_margin_m =
      0.05;  ///< a position this close behind a plane still counts as in front
  double max_tilt_rad =
      0.0872664626;  ///< 5°: roll/pitch allowance for regions (poses use their own)
};

/// The polygons kept and why the others were left out. considered = kept.size() + all counts.
struct CullResult {
  std::vector<int> kept;  ///< ascending indices into PlaneMap::polygons
  std::size_t considered = 0;
  std::size_t out_of_range = 0;
  std::size_t facing_away = 0;
  std::size_t outside_field_of_view = 0;
};

class PlaneCuller {
 public:
  /// Keeps references to `map` and `index` (built on the same map), which must outlive it.
  /// `max_range_m`: the sensor's maximum range (a localizer hands down its one sensor range:
  /// localizer/models/range_sensor.hpp).
  PlaneCuller(const maps::PlaneMap& map, const maps::PlaneIndex& index,
              const sensor::LaserCalibration& calibration, CullConfig config = {},
              double max_range_m = sensor::kMaxRange_m);

  /// Polygons that a sensor anywhere in `region_map` (map frame), tilted by at most
  /// config.max_tilt_rad, can see.
  CullResult cull(const Eigen::AlignedBox3d& region_map) const;
  /// Polygons a sensor at exactly this pose can see.
  CullResult cull(const Pose3& T_map_sensor) const;

  const CullConfig& config() const { return config_; }

 private:
  CullResult cull(const Eigen::AlignedBox3d& region_map, double tilt_rad) const;

  const maps::PlaneMap& map_;
  const maps::PlaneIndex& index_;
  CullConfig config_;
  double max_range_m_;
  double lowest_elevation_rad_ = 0.0;
  double highest_elevation_rad_ = 0.0;
  double lowest_offset_m_ = 0.0;   ///< smallest apex height o_k
  double highest_offset_m_ = 0.0;  ///< largest apex height o_k
};

}  // namespace conicloc::localizer
