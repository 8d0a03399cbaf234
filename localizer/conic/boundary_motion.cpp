#include "localizer/conic/boundary_motion.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace conicloc::localizer {
namespace {

// 1/r of a side at the beam (cos θ, sin θ); ≤ 0 where the side predicts no return.
double inverse_range(const BoundarySide& side, double cos_theta, double sin_theta) {
  if (side.polygon < 0) return 0.0;
  return side.a * cos_theta + side.b * sin_theta + side.c;
}

// The edge of a closed vertex ring nearest `point`: its distance and direction, where nearer than
// `best_distance`. An edge whose bounding box lies farther than that along an axis is not nearer:
// for a point on one edge of a long wall, that leaves out most of the others at a few comparisons
// each.
void nearest_edge_of_ring(const maps::Ring3& vertices, const Eigen::Vector3d& point,
                          double& best_distance, Eigen::Vector3d& best_direction) {
  const std::size_t n = vertices.size();
  const auto beyond = [&](int axis, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    const double p = point[axis];
    return std::min(a[axis], b[axis]) - p > best_distance ||
           p - std::max(a[axis], b[axis]) > best_distance;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d& a = vertices[i];
    const Eigen::Vector3d& b = vertices[(i + 1) % n];
    if (beyond(0, a, b) || beyond(1, a, b) || beyond(2, a, b)) continue;
    const Eigen::Vector3d edge = b - a;
    const double length2 = edge.squaredNorm();
    if (!(length2 > 0.0)) continue;
    const double s = std::clamp((point - a).dot(edge) / length2, 0.0, 1.0);
    const double distance = (a + s * edge - point).norm();
    if (distance < best_distance) {
      best_distance = distance;
      best_direction = edge / std::sqrt(length2);
    }
  }
}

// The direction of the boundary's edge in the map frame, or nullopt (see boundary_motion).
std::optional<Eigen::Vector3d> edge_direction(const maps::PlaneMap& map, const BoundarySide& before,
                                              const BoundarySide& after, double inverse_before,
                                              double inverse_after, const Eigen::Vector3d& point,
                                              double range_m, double edge_tolerance_m) {
  const double nearer_inverse = std::max(inverse_before, inverse_after);
  const bool both_hit = inverse_before > 0.0 && inverse_after > 0.0;
  if (both_hit && std::abs(inverse_before - inverse_after) <= 1e-3 * nearer_inverse) {
    // The two planes meet the beam together: the boundary runs along their intersection.
    const auto& n_before = map.polygons[static_cast<std::size_t>(before.polygon)].plane.normal;
    const auto& n_after = map.polygons[static_cast<std::size_t>(after.polygon)].plane.normal;
    const Eigen::Vector3d line = n_before.cross(n_after);
    if (line.norm() < 1e-6) return std::nullopt;  // one plane: the range does not change here
    return line.normalized();
  }
  // The nearer side's polygon ends (or begins) here: its rim.
  const int nearer = inverse_before >= inverse_after ? before.polygon : after.polygon;
  const maps::PlanarPolygon& polygon = map.polygons[static_cast<std::size_t>(nearer)];
  // Only an edge within the tolerance counts: the search starts just above it (one at it is kept).
  const double tolerance_m = edge_tolerance_m + 1e-3 * range_m;
  if (!(tolerance_m >= 0.0)) return std::nullopt;
  double distance = std::nextafter(tolerance_m, std::numeric_limits<double>::infinity());
  Eigen::Vector3d nearest = Eigen::Vector3d::UnitZ();
  const double beyond_tolerance = distance;
  nearest_edge_of_ring(polygon.outer, point, distance, nearest);
  for (const maps::Ring3& hole : polygon.holes) {
    nearest_edge_of_ring(hole, point, distance, nearest);
  }
  if (!(distance < beyond_tolerance)) return std::nullopt;
  return nearest;
}

}  // namespace

void BoundaryRates::clear() {
  for (auto& column : columns_) column.clear();
}

void BoundaryRates::add(const BoundaryMotion& motion, double sign) {
  for (int axis = 0; axis < 3; ++axis) {
    columns_[static_cast<std::size_t>(axis)].push_back(sign * motion.per_translation[axis]);
    columns_[static_cast<std::size_t>(axis) + 3].push_back(sign * motion.per_rotation[axis]);
  }
}

void BoundaryRates::shifts(const PoseOffset& offset, std::vector<double>& out) const {
  const double d[6] = {offset.translation.x(), offset.translation.y(), offset.translation.z(),
                       offset.rotation.x(),    offset.rotation.y(),    offset.rotation.z()};
  const std::size_t count = size();
  out.resize(count);
  double* shift = out.data();
  const double* first = columns_[0].data();
  for (std::size_t k = 0; k < count; ++k) shift[k] = first[k] * d[0];
  for (std::size_t axis = 1; axis < 6; ++axis) {
    const double* rate = columns_[axis].data();
    const double component = d[axis];
    for (std::size_t k = 0; k < count; ++k) shift[k] += rate[k] * component;
  }
}

PoseOffset pose_offset(const Pose3& T_centre, const Pose3& T) {
  const Eigen::Matrix3d R_centre_t = T_centre.linear().transpose();
  const Eigen::Matrix3d dR = R_centre_t * T.linear();
  PoseOffset offset;
  offset.translation = R_centre_t * (T.translation() - T_centre.translation());
  // vee((dR − dRᵀ)/2) = sin(angle)·axis: the rotation vector to first order.
  offset.rotation =
      0.5 * Eigen::Vector3d(dR(2, 1) - dR(1, 2), dR(0, 2) - dR(2, 0), dR(1, 0) - dR(0, 1));
  return offset;
}

std::optional<BoundaryMotion> boundary_motion(const maps::PlaneMap& map, const RingGeometry& ring,
                                              const Pose3& T_map_sensor, double azimuth_rad,
                                              const BoundarySide& before, const BoundarySide& after,
                                              double edge_tolerance_m) {
  const double cos_theta = std::cos(azimuth_rad);
  const double sin_theta = std::sin(azimuth_rad);
  const double inverse_before = inverse_range(before, cos_theta, sin_theta);
  const double inverse_after = inverse_range(after, cos_theta, sin_theta);
  const double nearer_inverse = std::max(inverse_before, inverse_after);
  if (!(nearer_inverse > 0.0)) return std::nullopt;
  const double range_m = 1.0 / nearer_inverse;
  const Eigen::Vector3d P = ring.point(azimuth_rad, range_m);  // sensor frame
  const auto direction = edge_direction(map, before, after, inverse_before, inverse_after,
                                        T_map_sensor * P, range_m, edge_tolerance_m);
  if (!direction) return std::nullopt;
  const Eigen::Vector3d U = T_map_sensor.linear().transpose() * *direction;
  // w = h − g·(h·U)/(g·U) (the header's derivation).
  const double rho2 = P.x() * P.x() + P.y() * P.y();
  const double rho = std::sqrt(rho2);
  if (!(rho > 0.0)) return std::nullopt;
  const Eigen::Vector3d g(-ring.sin_elevation * P.x() / rho, -ring.sin_elevation * P.y() / rho,
                          ring.cos_elevation);
  const Eigen::Vector3d h(-P.y() / rho2, P.x() / rho2, 0.0);
  const double g_u = g.dot(U);
  // The ring runs along the edge: no single crossing to follow.
  if (!(std::abs(g_u) > 1e-6)) return std::nullopt;
  const Eigen::Vector3d w = h - g * (h.dot(U) / g_u);
  BoundaryMotion motion;
  motion.azimuth_rad = azimuth_rad;
  motion.per_translation = -w;
  motion.per_rotation = w.cross(P);
  return motion;
}

}  // namespace conicloc::localizer
