#include "maps/navigation_builder.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <unordered_map>

namespace conicloc::maps {
namespace {

// Key of a boundary's geometry independent of its direction: sorted vertices rounded to 1 mm,
// so "B1" and "B1-REVERSE" (the same line seen from both cells) share it.
std::vector<std::array<long long, 3>> geometry_key(const RawBoundary& boundary,
                                                   const MapFrame& frame) {
  std::vector<std::array<long long, 3>> key;
  auto add = [&](const Ring3& ring) {
    for (const auto& p : ring) {
      const Eigen::Vector3d q = frame.to_map(p);
      key.push_back(
          {std::llround(q.x() * 1e3), std::llround(q.y() * 1e3), std::llround(q.z() * 1e3)});
    }
  };
  for (const auto& line : boundary.lines) add(line);
  for (const auto& polygon : boundary.polygons) add(polygon.outer);
  std::sort(key.begin(), key.end());
  key.erase(std::unique(key.begin(), key.end()), key.end());
  return key;
}

double polyline_length(const std::vector<Eigen::Vector3d>& line) {
  double length = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) length += (line[i] - line[i - 1]).norm();
  return length;
}

}  // namespace

NavigationGraph build_navigation_graph(const RawBuilding& raw, const std::vector<int>& cell_of_raw,
                                       const PlaneMap& map, const MapFrame& frame,
                                       const std::map<std::string, BoundaryInfo>& boundaries,
                                       std::vector<std::string>& warnings) {
  NavigationGraph graph;
  std::unordered_map<std::string, int> cell_by_id;
  for (std::size_t c = 0; c < map.cells.size(); ++c)
    cell_by_id.emplace(map.cells[c].id, static_cast<int>(c));

  // One node per cell, named after its State when the dual graph has one.
  std::vector<std::string> state_of_cell(map.cells.size());
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    if (cell_of_raw[r] >= 0) state_of_cell[cell_of_raw[r]] = raw.cells[r].state_id;
  }
  for (const auto& state : raw.states) {
    const auto it = cell_by_id.find(state.cell_id);
    if (it != cell_by_id.end()) state_of_cell[it->second] = state.id;
  }
  std::unordered_map<std::string, int> node_by_state;
  for (std::size_t c = 0; c < map.cells.size(); ++c) {
    NavNode node;
    node.cell = static_cast<int>(c);
    node.id = state_of_cell[c].empty() ? map.cells[c].id : state_of_cell[c];
    node.position = map.cells[c].representative_point;
    node_by_state.emplace(node.id, static_cast<int>(c));
    graph.nodes.push_back(std::move(node));
  }

  int unresolved = 0;
  for (const auto& transition : raw.transitions) {
    if (transition.state_ids.size() < 2) {
      ++unresolved;
      continue;
    }
    const auto from = node_by_state.find(transition.state_ids[0]);
    const auto to = node_by_state.find(transition.state_ids[1]);
    if (from == node_by_state.end() || to == node_by_state.end()) {
      ++unresolved;
      continue;
    }
    NavEdge edge;
    edge.id = transition.id;
    edge.from = from->second;
    edge.to = to->second;
    std::vector<Eigen::Vector3d> line;
    for (const auto& p : transition.line) line.push_back(frame.to_map(p));
    const auto boundary = boundaries.find(transition.boundary_id);
    if (boundary != boundaries.end() && boundary->second.door) {
      edge.through_door = true;
      edge.door_point = boundary->second.centre;
    } else if (line.size() >= 3) {
      edge.door_point = line[line.size() / 2];  // drawn lines pass the opening mid-way
    } else {
      edge.door_point = 0.5 * (graph.nodes[edge.from].position + graph.nodes[edge.to].position);
    }
    edge.weight_m = line.size() >= 2 ? polyline_length(line)
                                     : (graph.nodes[edge.from].position - edge.door_point).norm() +
                                           (edge.door_point - graph.nodes[edge.to].position).norm();
    graph.edges.push_back(std::move(edge));
  }
  if (unresolved > 0) {
    warnings.push_back(std::to_string(unresolved) +
                       " transitions skipped: they do not connect two states of cells in the map");
  }
  if (!raw.transitions.empty()) return graph;

  // No dual graph: connect cells that share a boundary (by id, or by identical geometry).
  std::map<std::vector<std::array<long long, 3>>, std::set<int>> cells_by_geometry;
  std::unordered_map<std::string, const RawBoundary*> boundary_by_id;
  for (const auto& boundary : raw.boundaries) boundary_by_id.emplace(boundary.id, &boundary);
  std::map<std::vector<std::array<long long, 3>>, const RawBoundary*> boundary_by_key;
  for (std::size_t r = 0; r < raw.cells.size(); ++r) {
    if (cell_of_raw[r] < 0) continue;
    for (const auto& id : raw.cells[r].boundary_ids) {
      const auto it = boundary_by_id.find(id);
      if (it == boundary_by_id.end()) continue;
      auto key = geometry_key(*it->second, frame);
      if (key.empty()) continue;
      cells_by_geometry[key].insert(cell_of_raw[r]);
      boundary_by_key.emplace(std::move(key), it->second);
    }
  }
  for (const auto& [key, cells] : cells_by_geometry) {
    if (cells.size() < 2) continue;
    const RawBoundary* boundary = boundary_by_key.at(key);
    const auto info = boundaries.find(boundary->id);
    const std::vector<int> members(cells.begin(), cells.end());
    for (std::size_t i = 0; i < members.size(); ++i) {
      for (std::size_t j = i + 1; j < members.size(); ++j) {
        NavEdge edge;
        edge.id = boundary->id;
        edge.from = members[i];
        edge.to = members[j];
        if (info != boundaries.end()) {
          edge.through_door = info->second.door;
          edge.door_point = info->second.centre;
        }
        edge.weight_m = (graph.nodes[edge.from].position - edge.door_point).norm() +
                        (edge.door_point - graph.nodes[edge.to].position).norm();
        graph.edges.push_back(std::move(edge));
      }
    }
  }
  return graph;
}

}  // namespace conicloc::maps
