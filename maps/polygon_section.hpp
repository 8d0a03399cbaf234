#pragma once
// Horizontal sections of planar polygons: what a floor plan cut at height z shows of a wall.

#include <Eigen/Core>
#include <vector>

#include "maps/planar_polygon.hpp"

namespace conicloc::maps {

/// A straight piece of a section, map frame (both ends at the section height).
struct SectionSegment {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
};

/// Pieces of the horizontal line {z = height_m} ∩ plane that lie inside the polygon (outer ring
/// minus holes), by even-odd pairing of the ring crossings along the line. Empty for polygons
/// within ~0.06° of horizontal (their section is all or nothing) and when the line misses.
std::vector<SectionSegment> horizontal_section(const PlanarPolygon& polygon, double height_m);

/// Pieces of the same line inside the polygon's holes: the openings (windows, doors cut as holes)
/// the section passes through.
std::vector<SectionSegment> horizontal_section_of_holes(const PlanarPolygon& polygon,
                                                        double height_m);

}  // namespace conicloc::maps
