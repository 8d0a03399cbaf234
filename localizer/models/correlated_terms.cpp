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
  return {std::move(surface), representatives.size()};
}

std::vector<double> surface_term_weights(std::span<const int> surface_of_term,
                                         std::span<const double> size_of_term,
                                         const SurfaceTally& tally, double correlation) {
  const std::size_t n = surface_of_term.size();
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) total += size_of_term[i];
  std::vector<double> weights(n, 1.0);
  if (!(total > 0.0)) return weights;
  const double mean_worth = tally.effective_terms(correlation) / total;
  double weighted = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const int surface = surface_of_term[i];
    weights[i] =
        surface < 0 ? mean_worth : 1.0 / (1.0 + (tally.returns_on(surface) - 1.0) * correlation);
    weighted += weights[i] * size_of_term[i];
  }
  if (!(weighted > 0.0)) return std::vector<double>(n, 1.0);
  for (double& weight : weights) weight *= total / weighted;
  return weights;
}

}  // namespace conicloc::localizer
