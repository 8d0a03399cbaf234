#include "sim/navigation_route.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "sim/ray_polygon.hpp"

namespace conicloc::sim {
namespace {

bool cell_usable(const maps::PlaneMap& map, int cell) {
  return cell < 0 || (cell < static_cast<int>(map.cells.size()) && map.cells[cell].navigable);
}

const maps::Ring2* footprint_of(const maps::PlaneMap& map, int cell) {
  if (cell < 0 || cell >= static_cast<int>(map.cells.size())) return nullptr;
  const auto& ring = map.cells[cell].footprint;
  return ring.size() >= 3 ? &ring : nullptr;
}

bool inside(const maps::PlaneMap& map, int cell, const Eigen::Vector3d& point) {
  const auto* ring = footprint_of(map, cell);
  return ring == nullptr || maps::ring_contains(*ring, point.head<2>());
}

// The segment stays inside the cell's footprint (sampled every 10 cm).
bool segment_inside(const maps::PlaneMap& map, int cell, const Eigen::Vector3d& a,
                    const Eigen::Vector3d& b) {
  const int steps = std::max(1, static_cast<int>((b - a).norm() / 0.1));
  for (int i = 0; i <= steps; ++i) {
    if (!inside(map, cell, a + (b - a) * (static_cast<double>(i) / steps))) return false;
  }
  return true;
}

// A person or robot walking straight from floor point a to floor point b meets no surface: the
// segment 1 m above the floors crosses no polygon (door openings are holes in walls). Edges of
// the navigation graph that are not doors (virtual boundaries of 2D models, models without door
// openings, storeys linked straight through a slab) are walkable only where this holds: the
// simulator never walks through walls, floors or ceilings.
bool walkable(const maps::PlaneMap& map, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d lift(0.0, 0.0, 1.0);
  const double length = (b - a).norm();
  if (length < 1e-9) return true;
  const Ray ray{a + lift, (b - a) / length};
  for (const auto& polygon : map.polygons) {
    if (intersect_polygon(polygon, ray, 1e-6, length)) return false;
  }
  return true;
}

// A point of `cell`'s footprint reachable from `from` in a straight walkable line, drawn
// uniformly over its bounding box (20 tries); nullopt when none was found.
std::optional<Eigen::Vector3d> wander_point(const maps::PlaneMap& map, int cell,
                                            const Eigen::Vector3d& from, std::mt19937_64& rng) {
  const auto* ring = footprint_of(map, cell);
  if (ring == nullptr) return std::nullopt;
  Eigen::AlignedBox2d box;
  for (const auto& p : *ring) box.extend(p);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int attempt = 0; attempt < 20; ++attempt) {
    const Eigen::Vector3d p(box.min().x() + u(rng) * box.sizes().x(),
                            box.min().y() + u(rng) * box.sizes().y(), from.z());
    if ((p - from).norm() > 1.0 && segment_inside(map, cell, from, p) && walkable(map, from, p))
      return p;
  }
  return std::nullopt;
}

Eigen::Vector3d node_floor_point(const maps::PlaneMap& map, const maps::NavNode& node) {
  Eigen::Vector3d p = node.position;
  if (node.cell >= 0 && node.cell < static_cast<int>(map.cells.size())) {
    p.z() = map.cells[node.cell].floor_z;
  }
  return p;
}

// Horizontal axis through a door, pointing from `from` to `to`: the normal of the wall the door
// is cut into (nearest wall plane around the door point), else the direction between the nodes.
Eigen::Vector3d door_axis(const maps::PlaneMap& map, const maps::NavEdge& edge,
                          const Eigen::Vector3d& from_point, const Eigen::Vector3d& to_point) {
  Eigen::Vector3d axis = to_point - from_point;
  axis.z() = 0.0;
  double best = 0.3;  // a wall farther from the door point than this is not its wall
  for (const auto& polygon : map.polygons) {
    if (polygon.kind != maps::SurfaceKind::Wall) continue;
    Eigen::AlignedBox3d box = polygon.bounds;
    box.min().array() -= 0.3;
    box.max().array() += 0.3;
    if (!box.contains(edge.door_point)) continue;
    const double distance = std::abs(polygon.plane.signed_distance(edge.door_point));
    if (distance < best) {
      best = distance;
      axis = Eigen::Vector3d(polygon.plane.normal.x(), polygon.plane.normal.y(), 0.0);
    }
  }
  if (axis.norm() < 1e-9) axis = Eigen::Vector3d::UnitX();
  axis.normalize();
  if (axis.dot(to_point - edge.door_point) < 0.0) axis = -axis;
  return axis;
}

}  // namespace

double door_floor_z(const maps::PlaneMap& map, const maps::NavEdge& edge) {
  double best = -std::numeric_limits<double>::infinity();
  for (const int node : {edge.from, edge.to}) {
    const int cell = map.navigation.nodes[node].cell;
    if (cell < 0 || cell >= static_cast<int>(map.cells.size())) continue;
    const double z = map.cells[cell].floor_z;
    if (z <= edge.door_point.z() + 0.05) best = std::max(best, z);
  }
  return std::isfinite(best) ? best : edge.door_point.z();
}

Route plan_navigation_route(const maps::PlaneMap& map, const RouteConfig& config,
                            std::mt19937_64& rng) {
  const auto& graph = map.navigation;
  const int node_count = static_cast<int>(graph.nodes.size());
  std::vector<std::vector<int>> incident(node_count);
  for (int e = 0; e < static_cast<int>(graph.edges.size()); ++e) {
    const auto& edge = graph.edges[e];
    if (edge.from < 0 || edge.to < 0 || edge.from >= node_count || edge.to >= node_count) continue;
    incident[edge.from].push_back(e);
    incident[edge.to].push_back(e);
  }
  int start = -1;
  if (!config.start_node.empty()) {
    for (int n = 0; n < node_count; ++n) {
      if (graph.nodes[n].id == config.start_node) start = n;
    }
    if (start < 0) throw std::invalid_argument("no navigation node '" + config.start_node + "'");
  } else {
    std::vector<int> candidates;
    for (int n = 0; n < node_count; ++n) {
      if (cell_usable(map, graph.nodes[n].cell)) candidates.push_back(n);
    }
    if (candidates.empty()) throw std::invalid_argument("the map has no navigable node");
    start = candidates[std::uniform_int_distribution<std::size_t>(0, candidates.size() - 1)(rng)];
  }

  Route route;
  std::vector<int> visits(node_count, 0);
  double length = 0.0;
  auto add = [&](const Eigen::Vector3d& p) {
    if (!route.waypoints.empty()) length += (p - route.waypoints.back().floor_point).norm();
    route.waypoints.push_back(Waypoint{p, std::nullopt});
  };
  int current = start;
  visits[current] = 1;
  route.nodes.push_back(current);
  add(node_floor_point(map, graph.nodes[current]));
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  while (length < config.length_m) {
    // The least visited usable neighbour, ties broken at random.
    int chosen = -1;
    double best_key = std::numeric_limits<double>::infinity();
    for (const int e : incident[current]) {
      const auto& edge = graph.edges[e];
      const int other = edge.from == current ? edge.to : edge.from;
      if (other == current || !cell_usable(map, graph.nodes[other].cell)) continue;
      if (!edge.through_door && !walkable(map, node_floor_point(map, graph.nodes[current]),
                                          node_floor_point(map, graph.nodes[other])))
        continue;
      const double key = visits[other] + 0.5 * unit(rng);
      if (key < best_key) {
        best_key = key;
        chosen = e;
      }
    }
    if (chosen < 0) {
      // No way out of this cell: walk about inside it (a node without edges: one point).
      const auto p = incident[current].empty()
                         ? std::nullopt
                         : wander_point(map, graph.nodes[current].cell,
                                        route.waypoints.back().floor_point, rng);
      if (!p) break;
      add(*p);
      continue;
    }
    const auto& edge = graph.edges[chosen];
    const int next = edge.from == current ? edge.to : edge.from;
    const int cell_here = graph.nodes[current].cell;
    const int cell_next = graph.nodes[next].cell;
    const Eigen::Vector3d here = node_floor_point(map, graph.nodes[current]);
    const Eigen::Vector3d there = node_floor_point(map, graph.nodes[next]);
    std::vector<Eigen::Vector3d> crossing;  // entry approach, door, exit approach
    if (edge.through_door) {
      Eigen::Vector3d door = edge.door_point;
      door.z() = door_floor_z(map, edge);
      const Eigen::Vector3d axis = door_axis(map, edge, here, there);
      double before_m = config.door_approach_m;
      while (before_m > 0.05 && !inside(map, cell_here, door - before_m * axis)) before_m *= 0.5;
      double after_m = config.door_approach_m;
      while (after_m > 0.05 && !inside(map, cell_next, door + after_m * axis)) after_m *= 0.5;
      crossing = {door - before_m * axis, door, door + after_m * axis};
    } else {
      crossing = {0.5 * (here + there)};
    }
    // Within the current cell: straight from where we are to the crossing if that stays inside
    // the footprint, else by the node's point; z interpolated along (stairs rise evenly).
    const Eigen::Vector3d at = route.waypoints.back().floor_point;
    if (!segment_inside(map, cell_here, at, crossing.front()) &&
        (at.head<2>() - here.head<2>()).norm() > 0.05) {
      const double total = (here - at).norm() + (crossing.front() - here).norm();
      const double w = total > 1e-9 ? (here - at).norm() / total : 0.5;
      add(Eigen::Vector3d(here.x(), here.y(), at.z() + w * (crossing.front().z() - at.z())));
    }
    for (const auto& p : crossing) add(p);
    route.edges.push_back(chosen);
    route.nodes.push_back(next);
    ++visits[next];
    current = next;
  }
  if (route.nodes.size() > 1) {
    // End in the middle of the last room.
    const Eigen::Vector3d last = node_floor_point(map, graph.nodes[current]);
    add(Eigen::Vector3d(last.x(), last.y(), route.waypoints.back().floor_point.z()));
  }
  return route;
}

}  // namespace conicloc::sim
