#pragma once
// Bounding-volume hierarchy over planar polygons: nearest hit of a ray in O(log n) polygon tests.

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "maps/planar_polygon.hpp"
#include "sim/ray_polygon.hpp"

namespace conicloc::sim {

struct PolygonHit {
  double range_m = 0.0;
  int polygon = -1;  ///< index into the vector given to PolygonBvh's constructor
};

class PolygonBvh {
 public:
  PolygonBvh() = default;
  /// Builds over `polygons` (binned surface area heuristic, ≤ 2 per leaf).
  explicit PolygonBvh(std::vector<maps::PlanarPolygon> polygons);

  /// Nearest polygon crossed by `ray` in (min_range_m, max_range_m).
  std::optional<PolygonHit> nearest_hit(const Ray& ray, double min_range_m,
                                        double max_range_m) const;

  /// Same, but tries polygon `hint` first (the last hit of the same laser is usually hit again),
  /// so the traversal starts with a short range bound. Result identical to nearest_hit().
  std::optional<PolygonHit> nearest_hit(const Ray& ray, double min_range_m, double max_range_m,
                                        int hint) const;

  const std::vector<maps::PlanarPolygon>& polygons() const { return polygons_; }
  std::size_t node_count() const { return nodes_.size(); }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int first = 0;  ///< leaf: first index into order_; inner: index of the left child
    int count = 0;  ///< leaf: number of polygons; inner: 0
    int right = 0;  ///< inner: index of the right child
  };
  int build(int begin, int end, std::vector<Eigen::Vector3d>& centroids);
  int split_by_area(int begin, int end, const std::vector<Eigen::Vector3d>& centroids,
                    const Eigen::AlignedBox3d& centroid_box);

  std::vector<maps::PlanarPolygon> polygons_;
  std::vector<int> order_;  ///< polygon indices, leaves reference contiguous ranges
  std::vector<Node> nodes_;
};

}  // namespace conicloc::sim
