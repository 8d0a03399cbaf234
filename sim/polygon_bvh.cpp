#include "sim/polygon_bvh.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace conicloc::sim {
namespace {

constexpr int kLeafSize = 2;

// Slab test (Kay & Kajiya): entry distance of the ray into the box, or +inf if it misses within
// [0, t_max]. `inverse` = 1 / direction component-wise, with zero components replaced by a tiny
// value so no 0·inf NaN arises; branch-free min/max per axis.
inline double box_entry(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& origin,
                        const Eigen::Vector3d& inverse, double t_max) {
  const Eigen::Array3d t0 = (box.min() - origin).array() * inverse.array();
  const Eigen::Array3d t1 = (box.max() - origin).array() * inverse.array();
  const double t_near = std::max(t0.min(t1).maxCoeff(), 0.0);
  const double t_far = std::min(t0.max(t1).minCoeff(), t_max);
  return t_near <= t_far ? t_near : std::numeric_limits<double>::infinity();
}

}  // namespace

PolygonBvh::PolygonBvh(std::vector<maps::PlanarPolygon> polygons) : polygons_(std::move(polygons)) {
  if (polygons_.empty()) return;
  order_.resize(polygons_.size());
  std::vector<Eigen::Vector3d> centroids(polygons_.size());
  for (std::size_t i = 0; i < polygons_.size(); ++i) {
    order_[i] = static_cast<int>(i);
    centroids[i] = polygons_[i].bounds.center();
    // Flat boxes (a wall of zero thickness) get a sliver of thickness so the slab test is robust.
    polygons_[i].bounds.min().array() -= 1e-9;
    polygons_[i].bounds.max().array() += 1e-9;
  }
  nodes_.reserve(2 * polygons_.size() / kLeafSize + 2);
  build(0, static_cast<int>(order_.size()), centroids);
}

int PolygonBvh::build(int begin, int end, std::vector<Eigen::Vector3d>& centroids) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Eigen::AlignedBox3d box;
  Eigen::AlignedBox3d centroid_box;
  for (int i = begin; i < end; ++i) {
    box.extend(polygons_[order_[i]].bounds);
    centroid_box.extend(centroids[order_[i]]);
  }
  nodes_[index].box = box;
  if (end - begin <= kLeafSize) {
    nodes_[index].first = begin;
    nodes_[index].count = end - begin;
    return index;
  }
  int axis = 0;
  centroid_box.diagonal().maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](int a, int b) { return centroids[a][axis] < centroids[b][axis]; });
  const int left = build(begin, middle, centroids);
  const int right = build(middle, end, centroids);
  nodes_[index].first = left;
  nodes_[index].count = 0;
  nodes_[index].right = right;
  return index;
}

std::optional<PolygonHit> PolygonBvh::nearest_hit(const Ray& ray, double min_range_m,
                                                  double max_range_m) const {
  return nearest_hit(ray, min_range_m, max_range_m, -1);
}

std::optional<PolygonHit> PolygonBvh::nearest_hit(const Ray& ray, double min_range_m,
                                                  double max_range_m, int hint) const {
  if (nodes_.empty()) return std::nullopt;
  std::optional<PolygonHit> best;
  double bound = max_range_m;
  if (hint >= 0 && hint < static_cast<int>(polygons_.size())) {
    if (const auto t = intersect_polygon(polygons_[hint], ray, min_range_m, bound)) {
      best = PolygonHit{*t, hint};
      bound = *t;
    }
  }
  Eigen::Vector3d inverse;
  for (int axis = 0; axis < 3; ++axis) {
    const double d = ray.direction[axis];
    inverse[axis] = 1.0 / (std::abs(d) > 1e-300 ? d : std::copysign(1e-300, d));
  }
  std::array<int, 64> stack{};
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    if (box_entry(node.box, ray.origin, inverse, bound) > bound) continue;
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int polygon = order_[i];
        if (polygon == hint) continue;
        if (const auto t = intersect_polygon(polygons_[polygon], ray, min_range_m, bound)) {
          best = PolygonHit{*t, polygon};
          bound = *t;
        }
      }
      continue;
    }
    // Visit the nearer child first so the bound shrinks early.
    const int left = node.first;
    const int right = node.right;
    const double t_left = box_entry(nodes_[left].box, ray.origin, inverse, bound);
    const double t_right = box_entry(nodes_[right].box, ray.origin, inverse, bound);
    if (t_left <= t_right) {
      if (t_right <= bound) stack[top++] = right;
      if (t_left <= bound) stack[top++] = left;
    } else {
      if (t_left <= bound) stack[top++] = left;
      if (t_right <= bound) stack[top++] = right;
    }
  }
  return best;
}

}  // namespace conicloc::sim
