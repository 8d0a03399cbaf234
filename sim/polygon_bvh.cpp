#include "sim/polygon_bvh.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

namespace conicloc::sim {
namespace {

constexpr int kLeafSize = 2;
// The surface area heuristic may split off one polygon at a time (a tree as deep as the map is
// long); below this depth the splits halve, so no leaf lies deeper than 32 + log2(n / 2) < 64
// levels for any n < 2^32, and the descents' stacks (at most a node per level and one) hold.
constexpr int kAreaSplitDepth = 32;
constexpr int kStackSize = 64;
static_assert(kStackSize >= kAreaSplitDepth + 32, "a descent's stack holds a node per level");

// A ray prepared for slab tests (Kay & Kajiya): `inverse` = 1 / direction component-wise, with
// zero components replaced by a tiny value so no 0·inf NaN arises.
struct SlabRay {
  double origin[3];
  double inverse[3];
};

// Entry distance of the ray into the box, or +inf if it misses within [0, t_max]. Per axis the
// slab is entered at min(t0, t1) and left at max(t0, t1), t = (bound − o)·inverse.
inline double box_entry(const Eigen::AlignedBox3d& box, const SlabRay& ray, double t_max) {
  double t_near = 0.0;
  double t_far = t_max;
  for (int axis = 0; axis < 3; ++axis) {
    const double t0 = (box.min()[axis] - ray.origin[axis]) * ray.inverse[axis];
    const double t1 = (box.max()[axis] - ray.origin[axis]) * ray.inverse[axis];
    t_near = std::max(t_near, std::min(t0, t1));
    t_far = std::min(t_far, std::max(t0, t1));
  }
  return t_near <= t_far ? t_near : std::numeric_limits<double>::infinity();
}

SlabRay slab_ray(const Ray& ray) {
  SlabRay slab;
  for (int axis = 0; axis < 3; ++axis) {
    const double d = ray.direction[axis];
    slab.origin[axis] = ray.origin[axis];
    slab.inverse[axis] = 1.0 / (std::abs(d) > 1e-300 ? d : std::copysign(1e-300, d));
  }
  return slab;
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
  build(0, static_cast<int>(order_.size()), centroids, 0);
}

// Surface area heuristic (MacDonald & Booth 1990), binned: the split whose children's boxes make
// the expected cost of a random ray smallest, cost ∝ area(L)·n(L) + area(R)·n(R). Falls back to
// the median on the longest centroid axis when all centroids share a bin.
int PolygonBvh::split_by_area(int begin, int end, const std::vector<Eigen::Vector3d>& centroids,
                              const Eigen::AlignedBox3d& centroid_box) {
  constexpr int kBins = 12;
  const auto area = [](const Eigen::AlignedBox3d& box) {
    if (box.isEmpty()) return 0.0;
    const Eigen::Vector3d d = box.diagonal();
    return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
  };
  double best_cost = std::numeric_limits<double>::infinity();
  int best_axis = -1;
  int best_bin = 0;  ///< the left child takes bins [0, best_bin)
  for (int axis = 0; axis < 3; ++axis) {
    const double lo = centroid_box.min()[axis];
    const double extent = centroid_box.max()[axis] - lo;
    if (!(extent > 1e-12)) continue;
    std::array<Eigen::AlignedBox3d, kBins> boxes;
    std::array<int, kBins> counts{};
    const auto bin_of = [&](int polygon) {
      return std::min(kBins - 1,
                      static_cast<int>((centroids[polygon][axis] - lo) / extent * kBins));
    };
    for (int i = begin; i < end; ++i) {
      const int bin = bin_of(order_[i]);
      boxes[bin].extend(polygons_[order_[i]].bounds);
      ++counts[bin];
    }
    // Sweep: right-side areas and counts accumulated from the top bin down.
    std::array<double, kBins> right_area{};
    std::array<int, kBins> right_count{};
    Eigen::AlignedBox3d right;
    int count = 0;
    for (int b = kBins - 1; b > 0; --b) {
      right.extend(boxes[b]);
      count += counts[b];
      right_area[b] = area(right);
      right_count[b] = count;
    }
    Eigen::AlignedBox3d left;
    int left_count = 0;
    for (int b = 1; b < kBins; ++b) {  // split between bin b−1 and bin b
      left.extend(boxes[b - 1]);
      left_count += counts[b - 1];
      if (left_count == 0 || right_count[b] == 0) continue;
      const double cost = area(left) * left_count + right_area[b] * right_count[b];
      if (cost < best_cost) {
        best_cost = cost;
        best_axis = axis;
        best_bin = b;
      }
    }
  }
  if (best_axis >= 0) {
    const double lo = centroid_box.min()[best_axis];
    const double extent = centroid_box.max()[best_axis] - lo;
    const auto middle = std::partition(order_.begin() + begin, order_.begin() + end, [&](int p) {
      return std::min(kBins - 1, static_cast<int>((centroids[p][best_axis] - lo) / extent *
                                                  kBins)) < best_bin;
    });
    const int index = static_cast<int>(middle - order_.begin());
    if (index > begin && index < end) return index;
  }
  return split_at_median(begin, end, centroids, centroid_box);
}

int PolygonBvh::split_at_median(int begin, int end, const std::vector<Eigen::Vector3d>& centroids,
                                const Eigen::AlignedBox3d& centroid_box) {
  int axis = 0;
  centroid_box.diagonal().maxCoeff(&axis);
  const int middle = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + middle, order_.begin() + end,
                   [&](int a, int b) { return centroids[a][axis] < centroids[b][axis]; });
  return middle;
}

int PolygonBvh::build(int begin, int end, std::vector<Eigen::Vector3d>& centroids, int depth) {
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
  const int middle = depth < kAreaSplitDepth ? split_by_area(begin, end, centroids, centroid_box)
                                             : split_at_median(begin, end, centroids, centroid_box);
  const int left = build(begin, middle, centroids, depth + 1);
  const int right = build(middle, end, centroids, depth + 1);
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
  std::optional<PolygonHit> best;
  if (hint >= 0 && hint < static_cast<int>(polygons_.size())) {
    try_polygon(hint, ray, min_range_m, max_range_m, best);
  }
  traverse(ray, min_range_m, max_range_m, hint, best);
  return best;
}

void PolygonBvh::try_polygon(int polygon, const Ray& ray, double min_range_m, double max_range_m,
                             std::optional<PolygonHit>& best) const {
  // A crossing at best's own distance is taken too, when its polygon's index is lower.
  const double limit =
      best ? std::nextafter(best->range_m, std::numeric_limits<double>::infinity()) : max_range_m;
  const auto t = intersect_polygon(polygons_[polygon], ray, min_range_m, limit);
  if (!t || (best && *t == best->range_m && polygon > best->polygon)) return;
  best = PolygonHit{*t, polygon};
}

void PolygonBvh::traverse(const Ray& ray, double min_range_m, double max_range_m, int skip,
                          std::optional<PolygonHit>& best) const {
  if (nodes_.empty()) return;
  double bound = best ? best->range_m : max_range_m;
  const SlabRay slab = slab_ray(ray);
  // Each stacked node keeps the entry distance found when its parent was opened: it is tested
  // against the (possibly shrunk) bound when popped, without a second slab test.
  struct Pending {
    int node;
    double entry;
  };
  std::array<Pending, kStackSize> stack;
  int top = 0;
  const double root_entry = box_entry(nodes_[0].box, slab, bound);
  if (root_entry <= bound) stack[top++] = {0, root_entry};
  while (top > 0) {
    const Pending pending = stack[--top];
    if (pending.entry > bound) continue;
    const Node& node = nodes_[pending.node];
    if (node.count > 0) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        const int polygon = order_[i];
        if (polygon == skip) continue;
        try_polygon(polygon, ray, min_range_m, max_range_m, best);
        if (best) bound = best->range_m;
      }
      continue;
    }
    // Visit the nearer child first so the bound shrinks early: push it last.
    const int left = node.first;
    const int right = node.right;
    const double t_left = box_entry(nodes_[left].box, slab, bound);
    const double t_right = box_entry(nodes_[right].box, slab, bound);
    if (t_left <= t_right) {
      if (t_right <= bound) stack[top++] = {right, t_right};
      if (t_left <= bound) stack[top++] = {left, t_left};
    } else {
      if (t_left <= bound) stack[top++] = {left, t_left};
      if (t_right <= bound) stack[top++] = {right, t_right};
    }
  }
}

void PolygonBvh::nearest_hits(std::span<const Ray> rays, double min_range_m, double max_range_m,
                              std::span<const int> hints,
                              std::span<std::optional<PolygonHit>> out) const {
  assert(hints.size() == rays.size() && out.size() == rays.size());
  if (rays.size() > kMaxFan) {  // fans of at most kMaxFan rays
    for (std::size_t first = 0; first < rays.size(); first += kMaxFan) {
      const std::size_t n = std::min(kMaxFan, rays.size() - first);
      nearest_hits(rays.subspan(first, n), min_range_m, max_range_m, hints.subspan(first, n),
                   out.subspan(first, n));
    }
    return;
  }
  const int polygon_count = static_cast<int>(polygons_.size());
  // The hints first: a hinted hit bounds its ray's segment [min, t]. The bounded rays, ordered
  // by their direction's height, so that halving the fan keeps neighbouring lasers together.
  std::array<int, kMaxFan> bounded;
  int bounded_count = 0;
  for (std::size_t k = 0; k < rays.size(); ++k) {
    out[k].reset();
    if (hints[k] >= 0 && hints[k] < polygon_count) {
      try_polygon(hints[k], rays[k], min_range_m, max_range_m, out[k]);
      if (out[k]) {
        bounded[bounded_count++] = static_cast<int>(k);
        continue;
      }
    }
    traverse(rays[k], min_range_m, max_range_m, hints[k], out[k]);
  }
  std::sort(bounded.begin(), bounded.begin() + bounded_count,
            [&](int a, int b) { return rays[a].direction.z() < rays[b].direction.z(); });
  share(rays, min_range_m, hints, std::span<const int>(bounded.data(), bounded_count), out);
}

void PolygonBvh::share(std::span<const Ray> rays, double min_range_m, std::span<const int> hints,
                       std::span<const int> fan, std::span<std::optional<PolygonHit>> out) const {
  if (fan.empty()) return;
  if (fan.size() == 1) {
    const int k = fan.front();
    traverse(rays[k], min_range_m, out[k]->range_m, hints[k], out[k]);
    return;
  }
  Eigen::AlignedBox3d region;
  for (const int k : fan) {
    region.extend(rays[k].origin + min_range_m * rays[k].direction);
    region.extend(rays[k].origin + out[k]->range_m * rays[k].direction);
  }
  // Every polygon a bounded segment crosses has a box that meets the segment's box, so the
  // region's, and so does each of its ancestors' boxes: descending the boxes that meet the region
  // collects them all.
  std::array<int, kMaxShared> shared;
  std::array<Eigen::AlignedBox3d, kMaxShared> boxes;
  int count = 0;
  std::array<int, kStackSize> stack;
  int top = 0;
  stack[top++] = 0;
  while (top > 0 && count >= 0) {
    const Node& node = nodes_[stack[--top]];
    if (!node.box.intersects(region)) continue;
    if (node.count == 0) {
      stack[top++] = node.right;
      stack[top++] = node.first;
      continue;
    }
    for (int i = node.first; i < node.first + node.count; ++i) {
      const maps::PlanarPolygon& polygon = polygons_[order_[i]];
      if (!polygon.bounds.intersects(region)) continue;
      if (count == kMaxShared) {
        count = -1;
        break;
      }
      shared[count] = order_[i];
      boxes[count++] = polygon.bounds;
    }
  }
  if (count < 0) {
    const std::size_t half = fan.size() / 2;
    share(rays, min_range_m, hints, fan.first(half), out);
    share(rays, min_range_m, hints, fan.subspan(half), out);
    return;
  }
  for (const int k : fan) {
    const SlabRay slab = slab_ray(rays[k]);
    for (int i = 0; i < count; ++i) {
      const int polygon = shared[i];
      if (polygon == hints[k] || box_entry(boxes[i], slab, out[k]->range_m) > out[k]->range_m) {
        continue;
      }
      try_polygon(polygon, rays[k], min_range_m, out[k]->range_m, out[k]);
    }
  }
}

}  // namespace conicloc::sim
