#pragma once
// PlaneMap: the building as planar landmarks, plus its cells, storeys and navigation graph.
// Map frame M: metric, right-handed, z up; file coordinates (after any geographic conversion)
// minus `origin`, so geometry stays near zero in double precision.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "maps/planar_polygon.hpp"

namespace conicloc::maps {

struct Storey {
  std::string name;
  double floor_z = 0.0;    ///< m, map frame
  double ceiling_z = 0.0;  ///< m, map frame
};

/// A space of the building (IndoorGML CellSpace and its subclasses).
struct Cell {
  std::string id;          ///< gml:id
  std::string name;        ///< gml:name, may be empty
  std::string class_name;  ///< local element name: CellSpace, GeneralSpace, TransitionSpace, ...
  bool navigable = true;   ///< false for NonNavigableSpace and similar
  int storey = -1;         ///< index into PlaneMap::storeys
  Eigen::AlignedBox3d bounds;
  Eigen::Vector3d representative_point = Eigen::Vector3d::Zero();  ///< inside the cell, at floor level
  Ring2 footprint;  ///< outline of the cell in the xy plane (map frame), counter-clockwise
  double floor_z = 0.0;
  double ceiling_z = 0.0;
  std::vector<int> polygons;  ///< indices into PlaneMap::polygons bounding this cell
};

/// A node of the navigation graph: one per cell (IndoorGML State).
struct NavNode {
  std::string id;  ///< gml:id of the State, or of the cell when the file has no dual graph
  int cell = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< map frame
};

/// An edge of the navigation graph (IndoorGML Transition), usually through a door.
struct NavEdge {
  std::string id;
  int from = -1;  ///< index into NavigationGraph::nodes
  int to = -1;
  bool through_door = false;
  Eigen::Vector3d door_point = Eigen::Vector3d::Zero();  ///< centre of the opening when through_door
  double weight_m = 0.0;  ///< length along the edge
};

struct NavigationGraph {
  std::vector<NavNode> nodes;
  std::vector<NavEdge> edges;
};

struct PlaneMap {
  std::vector<PlanarPolygon> polygons;
  std::vector<Cell> cells;
  std::vector<Storey> storeys;  ///< sorted by floor_z
  NavigationGraph navigation;

  /// File coordinates (metres, after any geographic-to-local conversion) of the map frame's zero.
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  std::string crs;  ///< the srsName as read, empty if none
  Eigen::AlignedBox3d bounds;  ///< map frame
};

}  // namespace conicloc::maps
