#pragma once
// Bounding-volume hierarchy over planar polygons: nearest hit of a ray in O(log n) polygon tests.

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "maps/planar_polygon.hpp"
#include "sim/ray_polygon.hpp"

namespace conicloc::sim {

/// Of two polygons crossed at the same distance (a floor and the ceiling below it, in a slab of
/// zero thickness) the one of lower index is the hit, whatever order they are tried in: the
/// answer does not depend on hints, fans or threads.
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

  /// The nearest hits of a fan of rays from about one point (a firing's lasers), each tried first
  /// against its hint (−1: none): out[k] is what nearest_hit(rays[k], min_range_m, max_range_m,
  /// hints[k]) returns. The hinted hits bound their rays; one traversal collects the polygons
  /// whose boxes meet the box of those bounded segments, and each such ray tests only those
  /// instead of descending the tree alone (the tree's top levels are shared by the fan). Rays
  /// whose hint they miss traverse alone; a fan whose box holds too many polygons is halved.
  /// More than kMaxFan rays are taken as fans of kMaxFan.
  void nearest_hits(std::span<const Ray> rays, double min_range_m, double max_range_m,
                    std::span<const int> hints, std::span<std::optional<PolygonHit>> out) const;

  static constexpr std::size_t kMaxFan = 32;
  /// Beyond this many polygons in a fan's box (a fan down a long corridor) their list would cost
  /// more than the rays' own descents: the fan is halved.
  static constexpr int kMaxShared = 32;

  const std::vector<maps::PlanarPolygon>& polygons() const { return polygons_; }
  std::size_t node_count() const { return nodes_.size(); }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    int first = 0;  ///< leaf: first index into order_; inner: index of the left child
    int count = 0;  ///< leaf: number of polygons; inner: 0
    int right = 0;  ///< inner: index of the right child
  };
  int build(int begin, int end, std::vector<Eigen::Vector3d>& centroids, int depth);
  /// Makes `polygon` the best hit if the ray crosses it in (min_range_m, max_range_m) and nearer
  /// than `best`, or as near with a lower index.
  void try_polygon(int polygon, const Ray& ray, double min_range_m, double max_range_m,
                   std::optional<PolygonHit>& best) const;
  /// Descends the tree for a hit better than `best` (try_polygon), skipping `skip`.
  void traverse(const Ray& ray, double min_range_m, double max_range_m, int skip,
                std::optional<PolygonHit>& best) const;
  /// nearest_hits() for the rays fan[i], each already bounded by its hint's hit in out.
  void share(std::span<const Ray> rays, double min_range_m, std::span<const int> hints,
             std::span<const int> fan, std::span<std::optional<PolygonHit>> out) const;
  int split_by_area(int begin, int end, const std::vector<Eigen::Vector3d>& centroids,
                    const Eigen::AlignedBox3d& centroid_box);
  int split_at_median(int begin, int end, const std::vector<Eigen::Vector3d>& centroids,
                      const Eigen::AlignedBox3d& centroid_box);

  std::vector<maps::PlanarPolygon> polygons_;
  std::vector<int> order_;  ///< polygon indices, leaves reference contiguous ranges
  std::vector<Node> nodes_;
};

}  // namespace conicloc::sim
