#include "calib/laser_observability.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

namespace conicloc::calib {
namespace {

constexpr std::array<const char*, 4> kNames = {"elevation", "vertical offset", "azimuth offset",
                                               "range offset"};

void append(std::string& text, const std::string& more) {
  text += (text.empty() ? "" : "; ") + more;
}

bool all_parallel(const std::vector<Eigen::Vector3d>& normals, double parallel_deg) {
  const double min_sine = std::sin(parallel_deg * M_PI / 180.0);
  for (const auto& n : normals) {
    if (n.cross(normals.front()).norm() >= min_sine) return false;
  }
  return true;
}

}  // namespace

LaserObservability laser_observability(const LaserView& view, const ObservabilityConfig& config) {
  LaserObservability result;
  const auto n = static_cast<int>(view.normals_sensor.size());
  if (n < 2) {
    result.missing = "sees " + std::to_string(n) + " plane(s) with at least " +
                     std::to_string(config.min_plane_returns) + " returns (" +
                     std::to_string(view.returns) + " returns on " +
                     std::to_string(view.planes_seen) + " planes); needs two non-parallel planes";
    return result;
  }
  if (all_parallel(view.normals_sensor, config.parallel_deg)) {
    result.missing = "sees only parallel planes (" + std::to_string(n) + ", normals within " +
                     std::to_string(static_cast<int>(config.parallel_deg)) +
                     " deg): elevation, offsets and azimuth are not separable";
    return result;
  }
  result.observable = {true, true, true, true};
  bool floor_like = false, wall_like = false;
  for (const auto& normal : view.normals_sensor) {
    floor_like = floor_like || std::abs(normal.z()) >= config.min_normal_component;
    wall_like = wall_like || normal.head<2>().norm() >= config.min_normal_component;
  }
  if (!floor_like) {
    result.observable[1] = false;
    append(result.missing, "vertical offset: no floor, ceiling or sloped plane in view");
  } else if (view.floor_range_sd_m < config.min_range_spread * view.floor_range_mean_m) {
    result.observable[1] = false;
    char text[160];
    std::snprintf(text, sizeof text,
                  "vertical offset: floor and ceiling seen at one range (%.2f ± %.2f m), not "
                  "separable from the elevation",
                  view.floor_range_mean_m, view.floor_range_sd_m);
    append(result.missing, text);
  }
  if (!wall_like) {
    result.observable[2] = false;
    append(result.missing, "azimuth offset: no wall in view");
  }
  // The remaining corrections: rank of their information, scaled to unit diagonal (so metres
  // and radians compare); a near-null direction flags every correction taking part in it.
  // A correction whose information is rounding noise next to the others' has none (e.g. the
  // elevation of a level laser at 0° on vertical walls: d(cos φ)/dφ = 0).
  const double negligible = 1e-12 * view.information.trace();
  std::vector<int> free;
  for (int i = 0; i < 4; ++i) {
    if (result.observable[i] && view.information(i, i) > negligible) free.push_back(i);
    if (result.observable[i] && view.information(i, i) <= negligible) {
      result.observable[i] = false;
      append(result.missing, std::string(kNames[i]) + ": no information");
    }
  }
  const auto m = static_cast<int>(free.size());
  if (m == 0) return result;
  Eigen::MatrixXd scaled(m, m);
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b < m; ++b) {
      scaled(a, b) =
          view.information(free[a], free[b]) /
          std::sqrt(view.information(free[a], free[a]) * view.information(free[b], free[b]));
    }
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
  std::string weak;
  for (int e = 0; e < m; ++e) {
    if (eigen.eigenvalues()(e) >= config.min_scaled_eigenvalue) continue;
    for (int a = 0; a < m; ++a) {
      if (std::abs(eigen.eigenvectors()(a, e)) < 0.3 || !result.observable[free[a]]) continue;
      result.observable[free[a]] = false;
      weak += (weak.empty() ? "" : ", ") + std::string(kNames[free[a]]);
    }
  }
  if (!weak.empty()) append(result.missing, weak + ": not separable from the planes in view");
  return result;
}

}  // namespace conicloc::calib
