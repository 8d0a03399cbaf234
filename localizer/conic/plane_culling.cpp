#include "localizer/conic/plane_culling.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::localizer {
namespace {

// Slack for the apex's horizontal shift under tilt and for rounding (metres).
constexpr double kSlack_m = 0.01;

// Largest horizontal distance between a point of box a and a point of box b.
double max_horizontal_distance(const Eigen::AlignedBox3d& a, const Eigen::AlignedBox3d& b) {
  const double dx =
      std::max(std::abs(a.max().x() - b.min().x()), std::abs(b.max().x() - a.min().x()));
  const double dy =
      std::max(std::abs(a.max().y() - b.min().y()), std::abs(b.max().y() - a.min().y()));
  return std::hypot(dx, dy) + kSlack_m;
}

// Largest signed distance of a box's points from a plane (attained at a corner).
double max_signed_distance(const maps::Plane& plane, const Eigen::AlignedBox3d& box) {
  double best = -std::numeric_limits<double>::infinity();
  for (int corner = 0; corner < 8; ++corner) {
    best = std::max(best, plane.signed_distance(
                              box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(corner))));
  }
  return best;
}

}  // namespace

PlaneCuller::PlaneCuller(const maps::PlaneMap& map, const maps::PlaneIndex& index,
                         const sensor::LaserCalibration& calibration, CullConfig config,
                         double max_range_m)
    : map_(map), index_(index), config_(config), max_range_m_(max_range_m) {
  bool first = true;
  for (const sensor::Laser& laser : calibration.lasers) {
    if (first) {
      lowest_elevation_rad_ = highest_elevation_rad_ = laser.elevation_rad;
      lowest_offset_m_ = highest_offset_m_ = laser.vertical_offset_m;
      first = false;
    }
    lowest_elevation_rad_ = std::min(lowest_elevation_rad_, laser.elevation_rad);
    highest_elevation_rad_ = std::max(highest_elevation_rad_, laser.elevation_rad);
    lowest_offset_m_ = std::min(lowest_offset_m_, laser.vertical_offset_m);
    highest_offset_m_ = std::max(highest_offset_m_, laser.vertical_offset_m);
  }
}

CullResult PlaneCuller::cull(const Eigen::AlignedBox3d& region_map) const {
  return cull(region_map, config_.max_tilt_rad);
}

CullResult PlaneCuller::cull(const Pose3& T_map_sensor) const {
  const Eigen::Vector3d t = T_map_sensor.translation();
  // Tilt: angle between the spin axis and the map's z axis.
  const double tilt = std::acos(std::clamp(T_map_sensor.linear()(2, 2), -1.0, 1.0));
  return cull(Eigen::AlignedBox3d(t, t), tilt);
}

CullResult PlaneCuller::cull(const Eigen::AlignedBox3d& region_map, double tilt_rad) const {
  CullResult result;
  result.considered = map_.polygons.size();
  if (region_map.isEmpty()) {
    result.out_of_range = result.considered;
    return result;
  }
  const std::vector<int> in_range = index_.within(region_map, max_range_m_);
  result.out_of_range = result.considered - in_range.size();
  // Cone slopes with the tilt allowance; past ±90° a ring can see anything above/below.
  const double up = highest_elevation_rad_ + tilt_rad;
  const double down = -lowest_elevation_rad_ + tilt_rad;
  const double up_slope = up < M_PI / 2 ? std::tan(up) : std::numeric_limits<double>::infinity();
  const double down_slope =
      down < M_PI / 2 ? std::tan(down) : std::numeric_limits<double>::infinity();
  const double apex_top = region_map.max().z() + highest_offset_m_ + kSlack_m;
  const double apex_bottom = region_map.min().z() + lowest_offset_m_ - kSlack_m;
  result.kept.reserve(in_range.size());
  for (const int index : in_range) {
    const maps::PlanarPolygon& polygon = map_.polygons[static_cast<std::size_t>(index)];
    if (config_.cull_back_faces && !polygon.two_sided &&
        max_signed_distance(polygon.plane, region_map) < -config_.back_face_margin_m) {
      ++result.facing_away;
      continue;
    }
    // Entirely above the highest cone: its lowest point, at the largest horizontal distance,
    // still rises faster than the steepest upward beam (and symmetrically below).
    const double horizontal = max_horizontal_distance(polygon.bounds, region_map);
    const double rise = polygon.bounds.min().z() - apex_top;
    const double drop = apex_bottom - polygon.bounds.max().z();
    if ((rise > 0.0 && rise > up_slope * horizontal) ||
        (drop > 0.0 && drop > down_slope * horizontal)) {
      ++result.outside_field_of_view;
      continue;
    }
    result.kept.push_back(index);
  }
  return result;
}

}  // namespace conicloc::localizer
