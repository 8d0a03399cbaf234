#include "maps/planar_polygon.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace conicloc::maps {
namespace {

// Drops the closing vertex and consecutive repeats (real files do both).
Ring3 clean_ring(const Ring3& ring, double tolerance_m) {
  Ring3 out;
  out.reserve(ring.size());
  for (const auto& p : ring) {
    if (out.empty() || (p - out.back()).norm() > tolerance_m) out.push_back(p);
  }
  while (out.size() > 1 && (out.front() - out.back()).norm() <= tolerance_m) out.pop_back();
  return out;
}

// Newell's vector: ½ Σ p_i × p_{i+1} = area · n for a planar ring (taken about `center` so large
// coordinates do not cancel).
Eigen::Vector3d newell_vector(const Ring3& ring, const Eigen::Vector3d& center) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector3d a = ring[i] - center;
    const Eigen::Vector3d b = ring[(i + 1) % ring.size()] - center;
    sum += a.cross(b);
  }
  return 0.5 * sum;
}

PlaneFrame frame_for(const Eigen::Vector3d& normal, const Eigen::Vector3d& origin) {
  PlaneFrame frame;
  frame.origin = origin;
  // e_u horizontal for walls (u runs along the wall, v up), x for level planes.
  const Eigen::Vector3d along = Eigen::Vector3d::UnitZ().cross(normal);
  frame.e_u = along.norm() > 1e-6 ? along.normalized()
                                  : (Eigen::Vector3d::UnitX() - normal.x() * normal).normalized();
  frame.e_v = normal.cross(frame.e_u);  // so e_u × e_v = n
  return frame;
}

}  // namespace

double signed_area(const Ring2& ring) {
  double twice = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const auto& a = ring[i];
    const auto& b = ring[(i + 1) % ring.size()];
    twice += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice;
}

Ring2 plan_view(const Ring3& ring) {
  Ring2 out;
  out.reserve(ring.size());
  for (const auto& p : ring) out.emplace_back(p.x(), p.y());
  return out;
}

bool ring_contains(const Ring2& ring, const Eigen::Vector2d& point) {
  bool inside = false;
  for (std::size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    const auto& a = ring[i];
    const auto& b = ring[j];
    if ((a.y() > point.y()) != (b.y() > point.y()) &&
        point.x() < (b.x() - a.x()) * (point.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

bool PlanarPolygon::contains_uv(const Eigen::Vector2d& uv) const {
  if (!ring_contains(outer_uv, uv)) return false;
  return std::none_of(holes_uv.begin(), holes_uv.end(),
                      [&](const Ring2& hole) { return ring_contains(hole, uv); });
}

SurfaceKind classify_surface(const Eigen::Vector3d& normal) {
  const double sin_10deg = std::sin(10.0 * M_PI / 180.0);
  const double cos_10deg = std::cos(10.0 * M_PI / 180.0);
  if (std::abs(normal.z()) < sin_10deg) return SurfaceKind::Wall;
  if (normal.z() > cos_10deg) return SurfaceKind::Floor;
  if (normal.z() < -cos_10deg) return SurfaceKind::Ceiling;
  return SurfaceKind::Slope;
}

bool make_planar_polygon(const Ring3& outer_in, const std::vector<Ring3>& holes_in,
                         PlanarPolygon& out) {
  const double kRepeatTolerance_m = 1e-9;
  const Ring3 outer = clean_ring(outer_in, kRepeatTolerance_m);
  if (outer.size() < 3) return false;

  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : outer) mean += p;
  mean /= static_cast<double>(outer.size());

  const Eigen::Vector3d newell = newell_vector(outer, mean);
  Eigen::AlignedBox3d extent;
  for (const auto& p : outer) extent.extend(p);
  const double diagonal = extent.diagonal().norm();
  // Zero area, or a sliver whose width is below 1e-9 of its length: no plane can be fitted.
  if (!(newell.norm() > 1e-9 * diagonal * diagonal) || !std::isfinite(newell.norm())) return false;

  // Least-squares plane through the vertex mean: normal = eigenvector of the smallest eigenvalue
  // of the scatter matrix; signed like Newell's vector so the ring orientation is kept.
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : outer) scatter += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  Eigen::Vector3d normal = eigen.eigenvectors().col(0);
  if (normal.dot(newell) < 0.0) normal = -normal;

  out = PlanarPolygon{};
  out.plane.normal = normal;
  out.plane.offset = -normal.dot(mean);
  out.frame = frame_for(normal, mean);

  double flatness = 0.0;
  auto to_plane = [&](const Ring3& ring, Ring3& ring3, Ring2& ring2) {
    for (const auto& p : ring) {
      flatness = std::max(flatness, std::abs(out.plane.signed_distance(p)));
      ring2.push_back(out.frame.project(p));
      ring3.push_back(out.frame.lift(ring2.back()));
    }
  };
  to_plane(outer, out.outer, out.outer_uv);
  double area = signed_area(out.outer_uv);

  for (const auto& hole_in : holes_in) {
    const Ring3 hole = clean_ring(hole_in, kRepeatTolerance_m);
    if (hole.size() < 3) continue;
    Ring3 hole3;
    Ring2 hole2;
    to_plane(hole, hole3, hole2);
    if (signed_area(hole2) > 0.0) {  // holes run clockwise about the normal
      std::reverse(hole2.begin(), hole2.end());
      std::reverse(hole3.begin(), hole3.end());
    }
    area += signed_area(hole2);
    out.holes.push_back(std::move(hole3));
    out.holes_uv.push_back(std::move(hole2));
  }
  out.area = area;
  out.flatness_m = flatness;

  // Area centroid of the outer ring: c = Σ (a_i + b_i)(a_i × b_i) / (6 A).
  Eigen::Vector2d centroid_uv = Eigen::Vector2d::Zero();
  const double outer_area = signed_area(out.outer_uv);
  for (std::size_t i = 0; i < out.outer_uv.size(); ++i) {
    const auto& a = out.outer_uv[i];
    const auto& b = out.outer_uv[(i + 1) % out.outer_uv.size()];
    centroid_uv += (a + b) * (a.x() * b.y() - b.x() * a.y());
  }
  centroid_uv /= 6.0 * outer_area;
  out.centroid = out.frame.lift(centroid_uv);

  for (const auto& p : out.outer) {
    out.bounds.extend(p);
    out.radius = std::max(out.radius, (p - out.centroid).norm());
  }
  out.kind = classify_surface(normal);
  return true;
}

}  // namespace conicloc::maps
