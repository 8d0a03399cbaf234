#include "sim/prism_building.hpp"

#include <stdexcept>

namespace conicloc::sim {

double PrismCell::floor_at(double x) const {
  if (floor_profile.empty()) return floor_z;
  for (std::size_t i = 1; i < floor_profile.size(); ++i) {
    const Eigen::Vector2d& a = floor_profile[i - 1];
    const Eigen::Vector2d& b = floor_profile[i];
    if (x <= b.x()) return a.y() + (b.y() - a.y()) * (x - a.x()) / (b.x() - a.x());
  }
  return floor_profile.back().y();
}

Eigen::Vector2d PrismCell::centroid() const {
  double area = 0.0;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < footprint.size(); ++i) {
    const Eigen::Vector2d& a = footprint[i];
    const Eigen::Vector2d& b = footprint[(i + 1) % footprint.size()];
    const double cross = a.x() * b.y() - b.x() * a.y();
    area += cross;
    sum += (a + b) * cross;
  }
  return sum / (3.0 * area);
}

Eigen::Vector3d PrismCell::state_point() const {
  const Eigen::Vector2d xy = state_xy ? *state_xy : centroid();
  return {xy.x(), xy.y(), floor_at(xy.x()) + 0.5};
}

const PrismCell& PrismBuilding::cell(const std::string& id) const {
  for (const auto& c : cells) {
    if (c.id == id) return c;
  }
  throw std::logic_error("no generated cell \"" + id + "\"");
}

}  // namespace conicloc::sim
