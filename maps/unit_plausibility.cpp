#include "maps/unit_plausibility.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <vector>

namespace conicloc::maps {
namespace {

double median_cell_height_m(const PlaneMap& map) {
  std::vector<double> heights;
  for (const auto& cell : map.cells) {
    const double height = cell.ceiling_z - cell.floor_z;
    if (height > 0.0) heights.push_back(height);
  }
  if (heights.empty()) return 0.0;
  std::nth_element(heights.begin(), heights.begin() + heights.size() / 2, heights.end());
  return heights[heights.size() / 2];
}

bool plausible(double height_m, double extent_m, bool measure_height, const UnitLimits& limits) {
  if (measure_height && height_m > 0.0 &&
      (height_m < limits.min_storey_height_m || height_m > limits.max_storey_height_m))
    return false;
  return extent_m <= limits.max_extent_m;
}

}  // namespace

UnitCheck check_units(const PlaneMap& map, double unit_scale, bool measure_height,
                      const UnitLimits& limits) {
  UnitCheck check;
  check.storey_height_m = median_cell_height_m(map);
  if (!map.bounds.isEmpty()) {
    const Eigen::Vector3d size = map.bounds.sizes();
    check.extent_m = std::max(size.x(), size.y());
  }
  check.plausible = plausible(check.storey_height_m, check.extent_m, measure_height, limits);
  if (check.plausible) return check;

  std::ostringstream problem;
  if (measure_height && check.storey_height_m > 0.0 &&
      (check.storey_height_m < limits.min_storey_height_m ||
       check.storey_height_m > limits.max_storey_height_m)) {
    problem << "storeys are " << check.storey_height_m
            << " m high (median floor to ceiling, not in " << limits.min_storey_height_m << ".."
            << limits.max_storey_height_m << " m)";
  } else {
    problem << "the building is " << check.extent_m << " m across (more than "
            << limits.max_extent_m << " m)";
  }
  problem << " with unit scale " << unit_scale;
  check.problem = problem.str();

  // Sizes in the file's own units, then the common units, the one nearest a 3 m storey first.
  const double height_file = check.storey_height_m / unit_scale;
  const double extent_file = check.extent_m / unit_scale;
  constexpr std::array<double, 5> kScales{0.001, 0.01, 0.0254, 0.3048, 1.0};
  double best_error = INFINITY;
  for (const double scale : kScales) {
    if (scale == unit_scale) continue;
    if (!plausible(height_file * scale, extent_file * scale, measure_height, limits)) continue;
    const double error =
        measure_height && height_file > 0.0 ? std::abs(std::log(height_file * scale / 3.0)) : 0.0;
    if (error < best_error) {
      best_error = error;
      check.suggested_unit_scale = scale;
    }
  }
  return check;
}

}  // namespace conicloc::maps
