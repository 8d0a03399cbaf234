#include "maps/storeys.hpp"

#include <algorithm>
#include <numeric>
#include <string>

namespace conicloc::maps {

void assign_storeys(PlaneMap& map, double min_step_m) {
  map.storeys.clear();
  std::vector<int> order(map.cells.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return map.cells[a].floor_z < map.cells[b].floor_z; });
  std::vector<std::vector<int>> groups;
  double previous_floor = 0.0;
  for (const int index : order) {
    const double floor = map.cells[index].floor_z;
    if (groups.empty() || floor - previous_floor > min_step_m) groups.emplace_back();
    groups.back().push_back(index);
    previous_floor = floor;
  }
  for (std::size_t s = 0; s < groups.size(); ++s) {
    Storey storey;
    storey.name = "storey " + std::to_string(s);
    storey.floor_z = map.cells[groups[s].front()].floor_z;
    std::vector<double> ceilings;
    for (const int index : groups[s]) {
      ceilings.push_back(map.cells[index].ceiling_z);
      map.cells[index].storey = static_cast<int>(s);
    }
    std::nth_element(ceilings.begin(), ceilings.begin() + ceilings.size() / 2, ceilings.end());
    storey.ceiling_z = ceilings[ceilings.size() / 2];
    map.storeys.push_back(storey);
  }
  for (auto& polygon : map.polygons) {
    if (polygon.cell >= 0) polygon.storey = map.cells[polygon.cell].storey;
  }
}

}  // namespace conicloc::maps
