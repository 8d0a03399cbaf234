#pragma once
// PrismBuilding: a building of prism cells (a footprint extruded between a floor and a ceiling)
// joined by door openings, as the building generator lays it out before it is written as
// IndoorGML. Map frame: metres, x east, y north, z up.

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "maps/planar_polygon.hpp"

namespace conicloc::sim {

struct PrismCell {
  std::string id;                                ///< gml:id (an XML NCName)
  std::string class_name = "navi:GeneralSpace";  ///< qualified element name
  std::string name;
  std::string description;
  maps::Ring2 footprint;  ///< counter-clockwise seen from above, open (last != first)
  double floor_z = 0.0;   ///< level floor, m
  /// Replaces the level floor by a profile along x: (x, z) points, increasing x, covering the
  /// footprint's x range (a stair: landing, flight, landing).
  std::vector<Eigen::Vector2d> floor_profile;
  /// Ceiling plane z = c0 + cx·x + cy·y as (c0, cx, cy); (height, 0, 0) for a level ceiling.
  Eigen::Vector3d ceiling = Eigen::Vector3d::Zero();
  /// Pillars: footprints (counter-clockwise) of voids from floor to ceiling, strictly inside the
  /// footprint. Precondition: a level floor and ceiling where there are pillars.
  std::vector<maps::Ring2> pillars;
  /// Where the cell's State stands (xy); the footprint's centroid when empty.
  std::optional<Eigen::Vector2d> state_xy;

  double floor_at(double x) const;
  double ceiling_at(double x, double y) const { return ceiling.dot(Eigen::Vector3d(1.0, x, y)); }
  Eigen::Vector2d centroid() const;
  /// The State's point: state_xy (or the centroid), 0.5 m above the floor as in real files.
  Eigen::Vector3d state_point() const;
};

/// A door: a vertical rectangle from p0 to p1 (xy), z0..z1, on a footprint edge of both cells it
/// joins, reaching down to their floors there.
struct DoorOpening {
  std::string id;
  std::string name;
  Eigen::Vector2d p0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d p1 = Eigen::Vector2d::Zero();
  double z0 = 0.0;
  double z1 = 0.0;
  std::array<std::string, 2> cells;  ///< ids; the boundary's normal points from first to second
};

struct PrismBuilding {
  std::string name;                  ///< gml:name of the document
  std::vector<std::string> summary;  ///< lines for the header comment
  std::vector<PrismCell> cells;
  std::vector<DoorOpening> doors;

  /// The cell with this id; throws std::logic_error when there is none (a generator bug).
  const PrismCell& cell(const std::string& id) const;
};

}  // namespace conicloc::sim
