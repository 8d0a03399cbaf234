#include "sim/box_building.hpp"

#include <algorithm>
#include <stdexcept>

namespace conicloc::sim {
namespace {

// A polygon whose normal points along `inward` (the ring is reversed when needed).
maps::PlanarPolygon face(maps::Ring3 outer, std::vector<maps::Ring3> holes,
                         const Eigen::Vector3d& inward, int cell, const std::string& id) {
  maps::PlanarPolygon polygon;
  if (!maps::make_planar_polygon(outer, holes, polygon)) throw std::logic_error("bad face " + id);
  if (polygon.plane.normal.dot(inward) < 0.0) {
    std::reverse(outer.begin(), outer.end());
    maps::make_planar_polygon(outer, holes, polygon);
  }
  polygon.cell = cell;
  polygon.storey = 0;
  polygon.source_id = id;
  return polygon;
}

Eigen::Vector3d v(double x, double y, double z) {
  return {x, y, z};
}

}  // namespace

maps::PlaneMap make_box_building(const BoxBuildingSize& size) {
  const double X = size.room_x_m;
  const double Y = size.room_y_m;
  const double H = size.height_m;
  const double door_y0 = Y / 2 - 0.45;
  const double door_y1 = Y / 2 + 0.45;
  const maps::Ring3 door = {v(X, door_y0, 0.05), v(X, door_y1, 0.05), v(X, door_y1, 2.1),
                            v(X, door_y0, 2.1)};
  const maps::Ring3 window = {v(2 * X, 1.0, 1.0), v(2 * X, Y - 1.0, 1.0), v(2 * X, Y - 1.0, 2.2),
                              v(2 * X, 1.0, 2.2)};
  maps::PlaneMap map;
  map.storeys.push_back({"ground", 0.0, H});
  for (int cell = 0; cell < 2; ++cell) {
    const double x0 = cell * X;
    const double x1 = x0 + X;
    const std::string name = cell == 0 ? "A" : "B";
    auto add = [&](const maps::Ring3& outer, const std::vector<maps::Ring3>& holes,
                   const Eigen::Vector3d& inward, const std::string& what) {
      map.polygons.push_back(face(outer, holes, inward, cell, name + "-" + what));
    };
    add({v(x0, 0, 0), v(x1, 0, 0), v(x1, Y, 0), v(x0, Y, 0)}, {}, v(0, 0, 1), "floor");
    add({v(x0, 0, H), v(x1, 0, H), v(x1, Y, H), v(x0, Y, H)}, {}, v(0, 0, -1), "ceiling");
    add({v(x0, 0, 0), v(x1, 0, 0), v(x1, 0, H), v(x0, 0, H)}, {}, v(0, 1, 0), "south");
    add({v(x0, Y, 0), v(x1, Y, 0), v(x1, Y, H), v(x0, Y, H)}, {}, v(0, -1, 0), "north");
    const std::vector<maps::Ring3> west_holes =
        cell == 1 ? std::vector<maps::Ring3>{door} : std::vector<maps::Ring3>{};
    const std::vector<maps::Ring3> east_holes =
        cell == 0 ? std::vector<maps::Ring3>{door} : std::vector<maps::Ring3>{window};
    add({v(x0, 0, 0), v(x0, Y, 0), v(x0, Y, H), v(x0, 0, H)}, west_holes, v(1, 0, 0), "west");
    add({v(x1, 0, 0), v(x1, Y, 0), v(x1, Y, H), v(x1, 0, H)}, east_holes, v(-1, 0, 0), "east");

    maps::Cell c;
    c.id = "cell-" + name;
    c.name = name;
    c.class_name = "GeneralSpace";
    c.storey = 0;
    c.bounds = Eigen::AlignedBox3d(v(x0, 0, 0), v(x1, Y, H));
    c.representative_point = v(x0 + X / 2, Y / 2, 0);
    c.footprint = {Eigen::Vector2d(x0, 0), Eigen::Vector2d(x1, 0), Eigen::Vector2d(x1, Y),
                   Eigen::Vector2d(x0, Y)};
    c.floor_z = 0.0;
    c.ceiling_z = H;
    for (int i = 0; i < 6; ++i) c.polygons.push_back(cell * 6 + i);
    map.cells.push_back(c);
    map.navigation.nodes.push_back({"state-" + name, cell, v(x0 + X / 2, Y / 2, 0)});
  }
  maps::NavEdge edge;
  edge.id = "transition-AB";
  edge.from = 0;
  edge.to = 1;
  edge.through_door = true;
  edge.door_point = v(X, Y / 2, 1.05);
  edge.weight_m = X;
  map.navigation.edges.push_back(edge);
  for (const auto& polygon : map.polygons) map.bounds.extend(polygon.bounds);
  return map;
}

}  // namespace conicloc::sim
