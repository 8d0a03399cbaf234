#pragma once
// Spatial index over a PlaneMap's polygons: "which polygons can a sensor at p see within range R".

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <memory>
#include <vector>

#include "maps/plane_map.hpp"

namespace conicloc::maps {

class PlaneIndex {
 public:
  /// Keeps a reference to `map`, which must outlive the index.
  explicit PlaneIndex(const PlaneMap& map);
  ~PlaneIndex();
  PlaneIndex(PlaneIndex&&) noexcept;
  PlaneIndex& operator=(PlaneIndex&&) noexcept;

  /// Indices (ascending) of every polygon whose closest point lies within `range_m` of `point`.
  /// Exact: no polygon within range is missed, none beyond range is returned.
  std::vector<int> within(const Eigen::Vector3d& point, double range_m) const;

  /// Same for a region: polygons within `range_m` of any point of the axis-aligned `box`
  /// (for culling against a whole particle cloud).
  std::vector<int> within(const Eigen::AlignedBox3d& box, double range_m) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Closest point of a polygon (with holes) to `point`, map frame.
Eigen::Vector3d closest_point(const PlanarPolygon& polygon, const Eigen::Vector3d& point);

/// Euclidean distance between a polygon (with holes) and an axis-aligned box (0 when they touch).
/// Exact: the minimum over the polygon's interior (box corner nearest the plane, or the box's
/// section by the plane) and over every ring edge (segment-box distance, piecewise quadratic).
/// An empty box is infinitely far away.
double distance_to_box(const PlanarPolygon& polygon, const Eigen::AlignedBox3d& box);

}  // namespace conicloc::maps
