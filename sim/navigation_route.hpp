#pragma once
// Routes along a map's navigation graph: room to room through the doors, as a walk that prefers
// the least visited neighbour (so it explores the building), long enough for a given distance.

#include <random>
#include <string>
#include <vector>

#include "maps/plane_map.hpp"
#include "sim/trajectory.hpp"

namespace conicloc::sim {

struct RouteConfig {
  double length_m = 60.0;        ///< stop once the route is at least this long
  double door_approach_m = 0.6;  ///< straight run through each door, on both sides
  /// A robot's or walker's body keeps the sensor this far from the walls of the room it crosses
  /// (beyond the sensor's 0.3 m blind zone): straight runs inside a room keep it, except where
  /// they start or end closer (a door's approach) and leave that wall at once.
  double clearance_m = 0.4;
  std::string start_node;        ///< id of the first node; empty: a random navigable one
};

struct Route {
  std::vector<Waypoint> waypoints;  ///< at floor level
  std::vector<int> nodes;           ///< navigation nodes visited, in order
  std::vector<int> edges;           ///< edges taken
};

/// Throws std::invalid_argument if the graph has no node in a navigable cell, or the start node
/// is unknown. A node without edges gives a route of one point.
Route plan_navigation_route(const maps::PlaneMap& map, const RouteConfig& config,
                            std::mt19937_64& rng);

/// Floor height of a door: the highest floor of the two cells at or below the door point.
double door_floor_z(const maps::PlaneMap& map, const maps::NavEdge& edge);

}  // namespace conicloc::sim
