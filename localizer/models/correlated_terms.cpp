#include "localizer/models/correlated_terms.hpp"

#include <cmath>

namespace conicloc::localizer {

Surfaces coplanar_surfaces(const maps::PlaneMap& map, double angle_rad, double offset_m) {
  std::vector<int> surface(map.polygons.size(), -1);
  std::vector<std::size_t> representatives;  // one polygon per surface
  const double min_cos = std::cos(angle_rad);
  for (std::size_t p = 0; p < map.polygons.size(); ++p) {
    const maps::Plane& plane = map.polygons[p].plane;
    for (std::size_t s = 0; s < representatives.size(); ++s) {
      const maps::Plane& other = map.polygons[representatives[s]].plane;
      if (plane.normal.dot(other.normal) >= min_cos &&
          std::abs(plane.offset - other.offset) <= offset_m) {
        surface[p] = static_cast<int>(s);
        break;
      }
    }
    if (surface[p] < 0) {
      surface[p] = static_cast<int>(representatives.size());
      representatives.push_back(p);
    }
  }
  std::vector<Eigen::Vector2d> horizontal_normal;
  for (const std::size_t p : representatives)
    horizontal_normal.push_back(map.polygons[p].plane.normal.head<2>());
  return {std::move(surface), representatives.size(), std::move(horizontal_normal)};
}

std::vector<double> direction_term_weights(std::span<const int> surface_of_term,
                                           double scan_returns, const SurfaceTally& tally,
                                           double correlation) {
  const std::size_t n = surface_of_term.size();
  std::vector<double> weights(n, 1.0);
  const double worth = tally.effective_terms(correlation);
  if (!(scan_returns > 0.0) || !(worth > 0.0)) return weights;
  const double tempering = worth / scan_returns;
  const Surfaces& surfaces = tally.surfaces();
  std::vector<int> seen;
  for (std::size_t k = 0; k < surfaces.count; ++k) {
    if (tally.returns_on(static_cast<int>(k)) > 0.0) seen.push_back(static_cast<int>(k));
  }
  constexpr double kMinSideways = 0.5;  // sin 30°: walls and steep slopes, not floors
  std::vector<double> raise(surfaces.count, 1.0);
  for (const int g : seen) {
    const Eigen::Vector2d& normal = surfaces.horizontal_normal[static_cast<std::size_t>(g)];
    const double length = normal.norm();
    if (!(length >= kMinSideways)) continue;
    const Eigen::Vector2d u = normal / length;
    double given = 0.0, worth_there = 0.0;  // E(u), W(u)
    for (const int k : seen) {
      const double c = surfaces.horizontal_normal[static_cast<std::size_t>(k)].dot(u);
      const double m = tally.returns_on(k);
      given += tempering * m * c * c;
      worth_there += m / (1.0 + (m - 1.0) * correlation) * c * c;
    }
    if (worth_there > given) raise[static_cast<std::size_t>(g)] = worth_there / given;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (surface_of_term[i] >= 0) weights[i] = raise[static_cast<std::size_t>(surface_of_term[i])];
  }
  return weights;
}

}  // namespace conicloc::localizer
