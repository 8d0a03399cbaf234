#include "maps/floorless_cells.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "maps/walkable_ground.hpp"

namespace conicloc::maps {

namespace {

// How far into the neighbour its ground is read: a door point lies on the wall line, the very
// edge of the neighbour's floor outline, where containment is undecided.
constexpr double kThresholdInset_m = 0.2;
// The floor at a door lies below its centre, and at a door-less edge's point within this.
constexpr double kThresholdReach_m = 0.5;

// The height of `neighbour`'s ground where `edge` enters it, if it has ground there.
std::optional<double> threshold_height(const PlaneMap& map, const NavEdge& edge, int neighbour,
                                       const Eigen::Vector3d& neighbour_node) {
  Eigen::Vector2d inward = neighbour_node.head<2>() - edge.door_point.head<2>();
  const double length = inward.norm();
  const Eigen::Vector2d at =
      length > kThresholdInset_m
          ? Eigen::Vector2d(edge.door_point.head<2>() + inward * (kThresholdInset_m / length))
          : Eigen::Vector2d(neighbour_node.head<2>());
  return ground_height_at(map, neighbour, at.x(), at.y(), edge.door_point.z() + kThresholdReach_m);
}

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t half = values.size() / 2;
  return values.size() % 2 == 1 ? values[half] : 0.5 * (values[half - 1] + values[half]);
}

}  // namespace

int assign_floors_to_floorless_cells(PlaneMap& map, std::vector<std::string>& warnings) {
  const auto& nodes = map.navigation.nodes;
  const auto node_count = static_cast<int>(nodes.size());
  std::vector<bool> has_floor(map.cells.size());
  for (std::size_t c = 0; c < map.cells.size(); ++c)
    has_floor[c] = cell_has_floor(map, static_cast<int>(c));
  std::vector<std::vector<double>> thresholds(map.cells.size());
  for (const NavEdge& edge : map.navigation.edges) {
    if (edge.from < 0 || edge.to < 0 || edge.from >= node_count || edge.to >= node_count) continue;
    for (const auto& [here, there] :
         {std::pair{edge.from, edge.to}, std::pair{edge.to, edge.from}}) {
      const int cell = nodes[static_cast<std::size_t>(here)].cell;
      const int neighbour = nodes[static_cast<std::size_t>(there)].cell;
      if (cell < 0 || neighbour < 0 || cell == neighbour) continue;
      if (!map.cells[static_cast<std::size_t>(cell)].navigable ||
          !map.cells[static_cast<std::size_t>(neighbour)].navigable ||
          has_floor[static_cast<std::size_t>(cell)] ||
          !has_floor[static_cast<std::size_t>(neighbour)])
        continue;
      const Cell& floorless = map.cells[static_cast<std::size_t>(cell)];
      const auto z =
          threshold_height(map, edge, neighbour, nodes[static_cast<std::size_t>(there)].position);
      if (z && *z >= floorless.floor_z && *z < floorless.ceiling_z)
        thresholds[static_cast<std::size_t>(cell)].push_back(*z);
    }
  }
  int assigned = 0;
  for (std::size_t c = 0; c < map.cells.size(); ++c) {
    if (thresholds[c].empty()) continue;
    Cell& cell = map.cells[c];
    const double floor_z = median(thresholds[c]);
    std::ostringstream warning;
    warning << std::fixed << std::setprecision(3) << "navigable cell \"" << cell.id
            << "\" has no floor surface: its floor is taken at its thresholds' " << floor_z
            << " m, not at its lowest vertex " << cell.floor_z << " m";
    warnings.push_back(warning.str());
    cell.floor_z = floor_z;
    cell.representative_point.z() = floor_z;
    for (NavNode& node : map.navigation.nodes) {
      if (node.cell == static_cast<int>(c)) node.position.z() = floor_z;
    }
    ++assigned;
  }
  return assigned;
}

}  // namespace conicloc::maps
