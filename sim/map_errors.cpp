#include "sim/map_errors.hpp"

#include <Eigen/Geometry>
#include <algorithm>

namespace conicloc::sim {
namespace {

maps::Ring3 transform_ring(const maps::Ring3& ring, const Eigen::Isometry3d& transform) {
  maps::Ring3 out;
  out.reserve(ring.size());
  for (const auto& p : ring) out.push_back(transform * p);
  return out;
}

}  // namespace

std::vector<maps::PlanarPolygon> perturb_walls(const std::vector<maps::PlanarPolygon>& polygons,
                                               double error_m, std::mt19937_64& rng) {
  std::vector<maps::PlanarPolygon> out = polygons;
  if (error_m <= 0.0) return out;
  std::normal_distribution<double> unit(0.0, 1.0);
  for (auto& polygon : out) {
    if (polygon.kind != maps::SurfaceKind::Wall) continue;
    const double shift_m = error_m * unit(rng);
    const double height_m = std::max(polygon.bounds.sizes().z(), 0.5);
    const double tilt_rad = error_m / height_m * unit(rng);
    const Eigen::Vector3d axis = polygon.frame.e_u;  // horizontal for walls
    Eigen::Isometry3d transform = Eigen::Isometry3d::Identity();
    transform.translate(polygon.centroid + shift_m * polygon.plane.normal);
    transform.rotate(Eigen::AngleAxisd(tilt_rad, axis));
    transform.translate(-polygon.centroid);
    std::vector<maps::Ring3> holes;
    for (const auto& hole : polygon.holes) holes.push_back(transform_ring(hole, transform));
    maps::PlanarPolygon moved;
    if (!maps::make_planar_polygon(transform_ring(polygon.outer, transform), holes, moved)) {
      continue;  // cannot happen for a valid wall under a rigid motion; keep it unperturbed
    }
    moved.cell = polygon.cell;
    moved.storey = polygon.storey;
    moved.source_id = polygon.source_id;
    polygon = std::move(moved);
  }
  return out;
}

}  // namespace conicloc::sim
