#include "sim/map_fit.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "parallel/parallel_for.hpp"

namespace conicloc::sim {
namespace {

// A return of the real walls, on the plane the map holds for the surface it hit.
struct MapReturn {
  Eigen::Vector3d point_sensor;
  const maps::Plane* plane;
};

std::vector<MapReturn> map_returns(const maps::PlaneMap& map, const World& world,
                                   const sensor::LaserCalibration& calibration,
                                   const Eigen::Isometry3d& T_map_sensor,
                                   const MapFitConfig& config) {
  std::vector<MapReturn> returns;
  const auto steps = static_cast<int>(std::ceil(2.0 * M_PI / config.azimuth_step_rad));
  for (const sensor::Laser& laser : calibration.lasers) {
    const double c = std::cos(laser.elevation_rad), s = std::sin(laser.elevation_rad);
    int hint = -1;
    for (int k = 0; k < steps; ++k) {
      const double azimuth = k * config.azimuth_step_rad;
      const Eigen::Vector3d direction_sensor(c * std::cos(azimuth), c * std::sin(azimuth), s);
      const Ray ray{T_map_sensor.translation(), T_map_sensor.linear() * direction_sensor};
      // From the origin, as the simulated sensor: a surface nearer than min_range_m blocks the
      // beam and returns nothing.
      const std::optional<WorldHit> hit =
          world.nearest_surface(ray, 0.0, config.max_range_m, hint);
      if (!hit || hit->polygon < 0) continue;
      hint = hit->polygon;
      if (!(hit->range_m > config.min_range_m)) continue;
      const auto k_polygon = static_cast<std::size_t>(hit->polygon);
      if (k_polygon >= map.polygons.size() ||
          world.materials()[k_polygon].origin != SurfaceOrigin::Map)
        continue;  // clutter: not the map's
      returns.push_back({hit->range_m * direction_sensor, &map.polygons[k_polygon].plane});
    }
  }
  return returns;
}

// The returns' RMS range L = √(Σ|p|² / n): the length that puts a rotation in metres.
double rms_range_m(const std::vector<MapReturn>& returns) {
  double sum_squares = 0.0;
  for (const MapReturn& r : returns) sum_squares += r.point_sensor.squaredNorm();
  return std::sqrt(sum_squares / static_cast<double>(returns.size()));
}

// One Gauss–Newton step: the correction ξ = (ω, v) of `T_map_sensor` (map_fit.hpp), over the
// directions the returns fix. The rotation is solved for as L·ω, L = rms_range_m(returns), so
// that both halves of the information are in m² and their eigenvalues compare.
Eigen::Matrix<double, 6, 1> correction(const std::vector<MapReturn>& returns, double length_m,
                                       const Eigen::Isometry3d& T_map_sensor,
                                       double min_information_ratio) {
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> gradient = Eigen::Matrix<double, 6, 1>::Zero();
  for (const MapReturn& r : returns) {
    const Eigen::Vector3d m = T_map_sensor.linear().transpose() * r.plane->normal;
    const double residual = r.plane->signed_distance(T_map_sensor * r.point_sensor);
    Eigen::Matrix<double, 6, 1> jacobian;  // ∂r/∂(L·ω), ∂r/∂v
    jacobian << r.point_sensor.cross(m) / length_m, m;
    information.selfadjointView<Eigen::Lower>().rankUpdate(jacobian);
    gradient += jacobian * residual;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> solver(
      information.selfadjointView<Eigen::Lower>());
  const Eigen::Matrix<double, 6, 1>& eigenvalues = solver.eigenvalues();  // ascending
  Eigen::Matrix<double, 6, 1> xi = Eigen::Matrix<double, 6, 1>::Zero();
  for (int j = 0; j < 6; ++j) {
    if (!(eigenvalues[j] > min_information_ratio * eigenvalues[5])) continue;
    const Eigen::Matrix<double, 6, 1> direction = solver.eigenvectors().col(j);
    xi -= direction * (direction.dot(gradient) / eigenvalues[j]);
  }
  xi.head<3>() /= length_m;
  return xi;
}

}  // namespace

std::vector<io::StampedPose> map_fit_poses(const maps::PlaneMap& map, const World& world,
                                           const sensor::LaserCalibration& calibration,
                                           std::span<const io::StampedPose> truth,
                                           const MapFitConfig& config) {
  std::vector<io::StampedPose> fitted(truth.begin(), truth.end());
  const auto fit = [&](std::size_t i) {
    const std::vector<MapReturn> returns =
        map_returns(map, world, calibration, truth[i].pose, config);
    if (returns.empty()) return;
    const double length_m = rms_range_m(returns);
    Eigen::Isometry3d& T = fitted[i].pose;
    for (int iteration = 0; iteration < config.iterations; ++iteration) {
      const Eigen::Matrix<double, 6, 1> xi =
          correction(returns, length_m, T, config.min_information_ratio);
      Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
      const double angle = xi.head<3>().norm();
      if (angle > 0.0) step.linear() = Eigen::AngleAxisd(angle, xi.head<3>() / angle).matrix();
      step.translation() = xi.tail<3>();
      T = T * step;
      if (angle < 1e-9 && xi.tail<3>().norm() < 1e-9) break;
    }
  };
  // Every pose is fitted on its own.
  parallel_for(truth.size(), std::max(config.threads, 1),
               [&](std::size_t begin, std::size_t end, int) {
                 for (std::size_t i = begin; i < end; ++i) fit(i);
               });
  return fitted;
}

}  // namespace conicloc::sim
