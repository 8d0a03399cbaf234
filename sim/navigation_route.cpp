#include "sim/navigation_route.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "maps/segment_distance.hpp"
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

// Distance from p to a wall: to its plane where p's foot lies on the wall, else to the nearest
// point of its edges (a door frame, the end of the wall), √(d² + e²).
double distance_to_wall(const maps::PlanarPolygon& wall, const Eigen::Vector3d& p) {
  const double d = wall.plane.signed_distance(p);
  const Eigen::Vector2d uv = wall.frame.project(p);
  if (wall.contains_uv(uv)) return std::abs(d);
  double e = maps::distance_to_ring(wall.outer_uv, uv);
  for (const auto& hole : wall.holes_uv) e = std::min(e, maps::distance_to_ring(hole, uv));
  return std::hypot(d, e);
}

// How far a body 1 m above floor point p stands from the nearest of `walls`, at most `limit_m`.
double wall_clearance(const maps::PlaneMap& map, const std::vector<int>& walls,
                      const Eigen::Vector3d& p, double limit_m) {
  const Eigen::Vector3d body = p + Eigen::Vector3d(0.0, 0.0, 1.0);
  double best = limit_m;
  for (const int w : walls) {
    best = std::min(best, distance_to_wall(map.polygons[static_cast<std::size_t>(w)], body));
  }
  return best;
}

// Whether the end of a straight run may lie nearer a wall than the clearance: a door's approach
// may, a point chosen to wander to may not.
enum class EndNearWall { Allowed, NotAllowed };

// The segment stays inside the cell's footprint (sampled every 10 cm) and `clearance_m` from
// the walls. A start nearer a wall (where the route stands) is allowed, and an end where `end`
// allows it, but the segment must leave that wall at least as fast as it moves along: at
// distance s from an end with clearance c, it keeps min(clearance_m, c + s).
bool segment_clear(const maps::PlaneMap& map, int cell, const Eigen::Vector3d& a,
                   const Eigen::Vector3d& b, double clearance_m, EndNearWall end) {
  const double length = (b - a).norm();
  const int steps = std::max(1, static_cast<int>(length / 0.1));
  // The walls near the segment, by their boxes; a stair's risers and other low walls are
  // stepped over, not walked beside.
  Eigen::AlignedBox3d reach(a.cwiseMin(b), a.cwiseMax(b));
  reach.min() -= Eigen::Vector3d(clearance_m, clearance_m, 0.0);
  reach.max() += Eigen::Vector3d(clearance_m, clearance_m, 2.0);
  std::vector<int> walls;
  for (int i = 0; i < static_cast<int>(map.polygons.size()); ++i) {
    const auto& polygon = map.polygons[static_cast<std::size_t>(i)];
    if (polygon.kind == maps::SurfaceKind::Wall && polygon.bounds.sizes().z() >= 1.0 &&
        polygon.bounds.intersects(reach))
      walls.push_back(i);
  }
  const double clear_a = wall_clearance(map, walls, a, clearance_m);
  const double clear_b =
      end == EndNearWall::Allowed ? wall_clearance(map, walls, b, clearance_m) : clearance_m;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    const Eigen::Vector3d p = a + (b - a) * t;
    // A crossing between cells lies on their boundary: the start (where the route stands, often
    // a door's exit) and an end the run may reach near a wall may lie on the footprint's edge.
    const bool on_edge_allowed = i == 0 || (i == steps && end == EndNearWall::Allowed);
    if (!on_edge_allowed && !inside(map, cell, p)) return false;
    const double needed =
        std::min({clearance_m, clear_a + t * length, clear_b + (1.0 - t) * length});
    if (wall_clearance(map, walls, p, clearance_m) < needed - 1e-9) return false;
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

// The first of `tries` points drawn uniformly over the bounding box of `cell`'s footprint (at
// height z) that `accept` takes; nullopt when none was, or the cell has no footprint.
template <typename Accept>
std::optional<Eigen::Vector3d> draw_in_cell(const maps::PlaneMap& map, int cell, double z,
                                            int tries, std::mt19937_64& rng, Accept accept) {
  const auto* ring = footprint_of(map, cell);
  if (ring == nullptr) return std::nullopt;
  Eigen::AlignedBox2d box;
  for (const auto& p : *ring) box.extend(p);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int attempt = 0; attempt < tries; ++attempt) {
    Eigen::Vector3d p(box.min().x() + u(rng) * box.sizes().x(),
                      box.min().y() + u(rng) * box.sizes().y(), z);
    if (accept(p)) return p;
  }
  return std::nullopt;
}

// A point of `cell`'s footprint reachable from `from` by a straight walkable run clear of the
// walls (20 tries); nullopt when none was found.
std::optional<Eigen::Vector3d> wander_point(const maps::PlaneMap& map, int cell,
                                            const Eigen::Vector3d& from, double clearance_m,
                                            std::mt19937_64& rng) {
  return draw_in_cell(map, cell, from.z(), 20, rng, [&](const Eigen::Vector3d& p) {
    return (p - from).norm() > 1.0 &&
           segment_clear(map, cell, from, p, clearance_m, EndNearWall::NotAllowed) &&
           walkable(map, from, p);
  });
}

// A point of `cell` from which a straight run reaches `to` and to which one comes from `from`,
// both clear of the walls (a way round the corner of an L-shaped room; 50 tries); z
// interpolated by distance. nullopt when none was found.
std::optional<Eigen::Vector3d> via_point(const maps::PlaneMap& map, int cell,
                                         const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                         double clearance_m, std::mt19937_64& rng) {
  const auto with_height = [&](Eigen::Vector3d p) {
    const double total = (p - from).head<2>().norm() + (to - p).head<2>().norm();
    if (total > 1e-9) p.z() = from.z() + (to.z() - from.z()) * (p - from).head<2>().norm() / total;
    return p;
  };
  const auto found = draw_in_cell(map, cell, from.z(), 50, rng, [&](const Eigen::Vector3d& q) {
    const Eigen::Vector3d p = with_height(q);
    return segment_clear(map, cell, from, p, clearance_m, EndNearWall::NotAllowed) &&
           segment_clear(map, cell, to, p, clearance_m, EndNearWall::NotAllowed) &&
           walkable(map, from, p) && walkable(map, p, to);
  });
  if (!found) return std::nullopt;
  return with_height(*found);
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

namespace {

// How the route crosses from node `from` to node `to` along `edge`: through a door, an approach
// on each side (door_approach_m along the door's axis, shortened to stay in each cell), the door
// point, the exit; else the midpoint between the nodes.
std::vector<Eigen::Vector3d> edge_crossing(const maps::PlaneMap& map, const maps::NavEdge& edge,
                                           int from, int to, const RouteConfig& config) {
  const auto& nodes = map.navigation.nodes;
  const Eigen::Vector3d here = node_floor_point(map, nodes[from]);
  const Eigen::Vector3d there = node_floor_point(map, nodes[to]);
  if (!edge.through_door) return {0.5 * (here + there)};
  Eigen::Vector3d door = edge.door_point;
  door.z() = door_floor_z(map, edge);
  const Eigen::Vector3d axis = door_axis(map, edge, here, there);
  double before_m = config.door_approach_m;
  while (before_m > 0.05 && !inside(map, nodes[from].cell, door - before_m * axis)) before_m *= 0.5;
  double after_m = config.door_approach_m;
  while (after_m > 0.05 && !inside(map, nodes[to].cell, door + after_m * axis)) after_m *= 0.5;
  return {door - before_m * axis, door, door + after_m * axis};
}


// The way within `cell` from where the route stands (`at`) to `entry` (a crossing's first
// point), as the points to walk by: straight (none) where that stays inside the footprint and
// clear of the walls, else by the cell's node point `here` where both runs are, else by a point
// found in the cell from which both are (round a corner), else by the node point anyway. z is
// interpolated along (stairs rise evenly). nullopt when the route stands at the node and no way
// was found: the crossing is out of reach from here (a wall between).
std::optional<std::vector<Eigen::Vector3d>> way_within_cell(
    const maps::PlaneMap& map, int cell, const Eigen::Vector3d& at, const Eigen::Vector3d& here,
    const Eigen::Vector3d& entry, double clearance_m, std::mt19937_64& rng) {
  const auto clear = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return segment_clear(map, cell, a, b, clearance_m, EndNearWall::Allowed) &&
           walkable(map, a, b);
  };
  const bool away_from_node = (at.head<2>() - here.head<2>()).norm() > 0.05;
  // Back through the crossing it came by (a boundary without a door): into the room first.
  const bool turning_back = (entry.head<2>() - at.head<2>()).norm() < 0.05;
  if (!(turning_back && away_from_node) && clear(at, entry)) return std::vector<Eigen::Vector3d>{};
  const double total = (here - at).norm() + (entry - here).norm();
  const double w = total > 1e-9 ? (here - at).norm() / total : 0.5;
  const Eigen::Vector3d by_node(here.x(), here.y(), at.z() + w * (entry.z() - at.z()));
  if (away_from_node && clear(at, by_node) && clear(by_node, entry)) {
    return std::vector<Eigen::Vector3d>{by_node};
  }
  if (const auto via = via_point(map, cell, at, entry, clearance_m, rng)) {
    return std::vector<Eigen::Vector3d>{*via};
  }
  // A cell whose footprint does not hold its own way (a stair's, drawn from its surfaces) is
  // crossed by its node, as the model's graph does.
  if (away_from_node) return std::vector<Eigen::Vector3d>{by_node};
  return std::nullopt;
}

}  // namespace

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
    // The least visited usable neighbour within reach, ties broken at random.
    int chosen = -1;
    std::vector<Eigen::Vector3d> way;       // to the chosen crossing
    std::vector<Eigen::Vector3d> crossing;  // the chosen edge's
    double best_key = std::numeric_limits<double>::infinity();
    const Eigen::Vector3d at = route.waypoints.back().floor_point;
    const Eigen::Vector3d here = node_floor_point(map, graph.nodes[current]);
    for (const int e : incident[current]) {
      const auto& edge = graph.edges[e];
      const int other = edge.from == current ? edge.to : edge.from;
      if (other == current || !cell_usable(map, graph.nodes[other].cell)) continue;
      if (!edge.through_door &&
          !walkable(map, here, node_floor_point(map, graph.nodes[other])))
        continue;
      // A door the model leaves closed (its wall has no opening there) is no way through either.
      std::vector<Eigen::Vector3d> through = edge_crossing(map, edge, current, other, config);
      // (One run from the approach to the exit: the door point lies on the wall's plane, where a
      // leg ending there would not meet it.)
      if (edge.through_door && !walkable(map, through.front(), through.back())) continue;
      const auto reach = way_within_cell(map, graph.nodes[current].cell, at, here,
                                         through.front(), config.clearance_m, rng);
      if (!reach) continue;
      const double key = visits[other] + 0.5 * unit(rng);
      if (key < best_key) {
        best_key = key;
        chosen = e;
        way = *reach;
        crossing = std::move(through);
      }
    }
    if (chosen < 0) {
      // No way out of this cell: walk about inside it (a node without edges: one point).
      const auto p = incident[current].empty()
                         ? std::nullopt
                         : wander_point(map, graph.nodes[current].cell,
                                        route.waypoints.back().floor_point, config.clearance_m,
                                        rng);
      if (!p) break;
      add(*p);
      continue;
    }
    const auto& edge = graph.edges[chosen];
    const int next = edge.from == current ? edge.to : edge.from;
    for (const auto& p : way) add(p);
    for (const auto& p : crossing) add(p);
    route.edges.push_back(chosen);
    route.nodes.push_back(next);
    ++visits[next];
    current = next;
  }
  if (route.nodes.size() > 1) {
    // End in the middle of the last room, where it can be reached.
    const Eigen::Vector3d at = route.waypoints.back().floor_point;
    const Eigen::Vector3d node = node_floor_point(map, graph.nodes[current]);
    const Eigen::Vector3d last(node.x(), node.y(), at.z());
    if (const auto way = way_within_cell(map, graph.nodes[current].cell, at, last, last,
                                         config.clearance_m, rng)) {
      for (const auto& p : *way) add(p);
      add(last);
    }
  }
  return route;
}

}  // namespace conicloc::sim
