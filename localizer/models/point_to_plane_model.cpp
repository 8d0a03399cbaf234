#include "localizer/models/point_to_plane_model.hpp"

#include <algorithm>
#include <cmath>
#include <nanoflann.hpp>

#include "localizer/models/correlated_terms.hpp"

namespace conicloc::localizer {

namespace {

// Points on the polygon: a uv grid inside it plus its outline, so the nearest sample is never
// farther than ~spacing/√2 from the nearest point of the polygon.
void sample_polygon(const maps::PlanarPolygon& polygon, double spacing_m,
                    std::vector<Eigen::Vector3d>& points) {
  Eigen::AlignedBox2d box;
  for (const auto& uv : polygon.outer_uv) box.extend(uv);
  for (double u = box.min().x() + 0.5 * spacing_m; u < box.max().x(); u += spacing_m) {
    for (double v = box.min().y() + 0.5 * spacing_m; v < box.max().y(); v += spacing_m) {
      if (polygon.contains_uv({u, v})) points.push_back(polygon.frame.lift({u, v}));
    }
  }
  const auto outline = [&](const maps::Ring3& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector3d& a = ring[i];
      const Eigen::Vector3d& b = ring[(i + 1) % ring.size()];
      const int steps = std::max(1, static_cast<int>(std::ceil((b - a).norm() / spacing_m)));
      for (int s = 0; s < steps; ++s)
        points.push_back(a + (b - a) * (static_cast<double>(s) / steps));
    }
  };
  outline(polygon.outer);
  for (const auto& hole : polygon.holes) outline(hole);
}

}  // namespace

struct PointToPlaneModel::Samples {
  std::vector<Eigen::Vector3d> points;
  std::vector<int> polygon;  ///< owning polygon of each point

  // nanoflann dataset adaptor interface.
  std::size_t kdtree_get_point_count() const { return points.size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return points[i][dim]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;
  }

  using Tree = nanoflann::KDTreeSingleIndexAdaptor<
      nanoflann::L2_Simple_Adaptor<double, Samples, double, std::size_t>, Samples, 3, std::size_t>;
  std::unique_ptr<Tree> tree;
};

PointToPlaneModel::PointToPlaneModel(const maps::PlaneMap& map, const RangeSensor& sensor,
                                     const PointToPlaneConfig& config)
    : map_(map),
      config_(config),
      sensor_(sensor),
      noise_(sensor.noise),
      samples_(std::make_unique<Samples>()),
      surfaces_(coplanar_surfaces(map)) {
  for (std::size_t p = 0; p < map.polygons.size(); ++p) {
    sample_polygon(map.polygons[p], config_.sample_spacing_m, samples_->points);
    samples_->polygon.resize(samples_->points.size(), static_cast<int>(p));
  }
  samples_->tree =
      std::make_unique<Samples::Tree>(3, *samples_, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  if (!samples_->points.empty()) samples_->tree->buildIndex();
  set_pose_blur(0.0);
  uniform_density_ = (1.0 - config_.hit_weight) / config_.max_distance_m;
}

void PointToPlaneModel::set_pose_blur(double blur_m) {
  noise_ = with_pose_blur(sensor_.noise, blur_m);
  log_hit_scale_ = std::log(config_.hit_weight / (std::sqrt(2.0 * M_PI) * noise_.sigma_m));
}

PointToPlaneModel::~PointToPlaneModel() = default;

std::size_t PointToPlaneModel::sample_count() const {
  return samples_->points.size();
}

void PointToPlaneModel::prepare(const sensor::Scan& scan,
                                const Eigen::AlignedBox3d& /*cloud_box*/) {
  const auto beams = select_beams(scan, config_.beams, sensor_.max_range_m);
  std::size_t count = 0;
  for (const auto& ring : beams) count += ring.size();
  points_sensor_.resize(3, static_cast<Eigen::Index>(count));
  Eigen::Index column = 0;
  for (const auto& ring : beams) {
    for (const SelectedBeam& beam : ring) {
      sensor::Return ret;
      ret.azimuth_rad = beam.azimuth_rad;
      ret.range_m = beam.range_m;
      points_sensor_.col(column++) = sensor::sensor_point(scan.rings[beam.ring], ret);
    }
  }
}

double PointToPlaneModel::distance_to_map(const Eigen::Vector3d& point_map) const {
  return nearest_polygon(point_map).distance_m;
}

PointToPlaneModel::Nearest PointToPlaneModel::nearest_polygon(
    const Eigen::Vector3d& point_map) const {
  Nearest nearest{config_.max_distance_m, -1};
  if (samples_->points.empty() || !point_map.allFinite()) return nearest;
  constexpr int kMaxCandidates = 16;
  const int k = std::clamp(config_.candidates, 1, kMaxCandidates);
  std::size_t indices[kMaxCandidates];
  double squared[kMaxCandidates];
  const std::size_t found = samples_->tree->knnSearch(point_map.data(), k, indices, squared);
  if (found == 0) return nearest;
  double best = std::sqrt(squared[0]);  // sample distance: an upper bound within ~spacing
  int best_polygon = samples_->polygon[indices[0]];
  for (std::size_t i = 0; i < found; ++i) {
    const int p = samples_->polygon[indices[i]];
    bool repeated = false;
    for (std::size_t j = 0; j < i; ++j) repeated |= samples_->polygon[indices[j]] == p;
    if (repeated) continue;
    const maps::PlanarPolygon& polygon = map_.polygons[p];
    // Where the foot of the perpendicular falls inside the polygon, the plane distance is exact.
    if (polygon.contains_uv(polygon.frame.project(point_map))) {
      const double distance = std::abs(polygon.plane.signed_distance(point_map));
      if (distance < best) best = distance, best_polygon = p;
    }
  }
  if (best >= config_.max_distance_m) return nearest;
  return {best, best_polygon};
}

double PointToPlaneModel::effective_terms(const Pose3& T_map_sensor, Scratch*) const {
  // The points this pose explains (within the inlier gate) grouped by the surface (plane) of
  // their nearest polygon; the others count nothing (correlated_terms.hpp).
  const double gate_m = noise_.inlier_gate_m();
  SurfaceTally tally(surfaces_);
  for (Eigen::Index i = 0; i < points_sensor_.cols(); ++i) {
    const Nearest nearest = nearest_polygon(T_map_sensor * points_sensor_.col(i));
    if (nearest.polygon >= 0 && nearest.distance_m <= gate_m) tally.add(nearest.polygon, 1.0);
  }
  return tally.effective_terms(noise_.shared_error_correlation());
}

ObservationScore PointToPlaneModel::score(const Pose3& T_map_sensor, Scratch* /*scratch*/) const {
  ObservationScore result;
  const Eigen::Index n = points_sensor_.cols();
  if (n == 0) return result;
  const double inlier_gate = noise_.inlier_gate_m();
  const double inverse_two_var = 0.5 / (noise_.sigma_m * noise_.sigma_m);
  std::size_t inliers = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double d = distance_to_map(T_map_sensor * points_sensor_.col(i));
    // log(w_hit·N(d; 0, σ) + w_rand/d_max), computed without underflow of the Gaussian.
    const double log_hit = log_hit_scale_ - d * d * inverse_two_var;
    const double log_rand = std::log(uniform_density_);
    const double hi = std::max(log_hit, log_rand);
    result.log_likelihood += hi + std::log1p(std::exp(std::min(log_hit, log_rand) - hi));
    inliers += d <= inlier_gate ? 1 : 0;
  }
  result.inlier_fraction = static_cast<double>(inliers) / static_cast<double>(n);
  return result;
}

}  // namespace conicloc::localizer
