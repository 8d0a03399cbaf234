#include "localizer/conic/polygon_groups.hpp"

#include <cmath>

namespace conicloc::localizer {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

}  // namespace

bool sphere_elevation_band(const Eigen::Vector3d& centre, double radius, double max_offset_m,
                           double& lo, double& hi) {
  const double distance = centre.norm();
  const double reach = radius + max_offset_m;  // apex shift ⊂ a bigger sphere
  if (!(distance > reach * (1.0 + 1e-9) + 1e-9)) return false;
  const double middle =
      std::atan2(centre.z(), std::sqrt(centre.x() * centre.x() + centre.y() * centre.y()));
  const double half = std::asin(reach / distance) + 1e-9;
  lo = middle - half;
  hi = middle + half;
  return true;
}

SensorBox sensor_box(const Eigen::AlignedBox3d& box, const Pose3& T_map_sensor,
                     double max_offset_m) {
  const Eigen::Matrix3d R_t = T_map_sensor.linear().transpose();
  const Eigen::Vector3d t = T_map_sensor.translation();
  const Eigen::Vector3d centre = R_t * (box.center() - t);
  // The box's half extents along the sensor axes: e_i = Σ_j |R_t(i, j)| h_j.
  const Eigen::Vector3d extent = R_t.cwiseAbs() * (0.5 * box.sizes());
  SensorBox out;
  out.nearest_m = box.exteriorDistance(t) - max_offset_m;
  out.z_low = centre.z() - extent.z();
  out.z_high = centre.z() + extent.z();

  // Its projection lies within the rectangle centre ± (e_x, e_y), so within the disc of radius
  // |(e_x, e_y)|; the disc spans centre azimuth ± asin(radius / ρ) unless it holds the z axis.
  const double disc = std::sqrt(extent.x() * extent.x() + extent.y() * extent.y());
  const double rho = std::sqrt(centre.x() * centre.x() + centre.y() * centre.y());
  if (rho > disc * (1.0 + 1e-9) + 1e-9) {
    const double half = std::asin(disc / rho) + kAzimuthSlack_rad;
    double begin = std::atan2(centre.y(), centre.x()) - half;
    if (begin < 0.0) begin += kTwoPi;
    if (begin >= kTwoPi) begin -= kTwoPi;
    out.span = {.whole = false, .begin_rad = begin, .width_rad = 2.0 * half};
  }

  // The box lies in the sphere of radius |e| around its centre.
  if (!sphere_elevation_band(centre, extent.norm(), max_offset_m, out.elevation_low,
                             out.elevation_high)) {
    out.elevation_low = -10.0;
    out.elevation_high = 10.0;
  }
  return out;
}

PolygonGroups::PolygonGroups(const maps::PlaneMap& map) {
  boxes_.resize(map.cells.size());
  group_of_.resize(map.polygons.size());
  for (std::size_t p = 0; p < map.polygons.size(); ++p) {
    const maps::PlanarPolygon& polygon = map.polygons[p];
    int group = polygon.cell;
    if (group < 0 || static_cast<std::size_t>(group) >= map.cells.size()) {
      group = static_cast<int>(boxes_.size());
      boxes_.emplace_back();
    }
    group_of_[p] = group;
    for (const Eigen::Vector3d& vertex : polygon.outer) {
      boxes_[static_cast<std::size_t>(group)].extend(vertex);
    }
  }
}

}  // namespace conicloc::localizer
