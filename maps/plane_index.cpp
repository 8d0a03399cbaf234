// PlaneIndex: a nanoflann k-d tree over bounding spheres of polygon pieces, then an exact filter.
//
// Every polygon is covered by spheres ("pieces"): its own bounding sphere when small, else one
// sphere per square tile of its plane that touches it, so one large floor does not widen every
// query. A polygon within range R of a query has a point within R of the query, and that point
// lies in a piece of radius r <= r_max, so the piece centre lies within R + r_max: a radius
// search over the piece centres finds every candidate. Candidates are then kept only when the
// exact distance (closest_point / distance_to_box) is within R.
#include "maps/plane_index.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <nanoflann.hpp>
#include <numeric>
#include <utility>

namespace conicloc::maps {
namespace {

struct Piece {
  Eigen::Vector3d center;
  double radius_m = 0.0;
  int polygon = -1;
};

// nanoflann dataset adaptor over the piece centres.
struct PieceCloud {
  std::vector<Piece> pieces;

  std::size_t kdtree_get_point_count() const { return pieces.size(); }
  double kdtree_get_pt(std::size_t index, std::size_t dim) const {
    return pieces[index].center[static_cast<Eigen::Index>(dim)];
  }
  template <class Box>
  bool kdtree_get_bbox(Box& /*box*/) const {
    return false;
  }
};

using KdTree = nanoflann::KDTreeSingleIndexAdaptor<
    nanoflann::L2_Simple_Adaptor<double, PieceCloud, double, std::size_t>, PieceCloud, 3,
    std::size_t>;

constexpr double kMinPieceRadius_m = 0.5;
constexpr double kMaxTilesPerPolygon = 4096.0;

// Distance in uv from a point to the polygon's region (0 inside, holes excluded).
double distance_to_region(const PlanarPolygon& polygon, const Eigen::Vector2d& p) {
  if (polygon.contains_uv(p)) return 0.0;
  double best2 = std::numeric_limits<double>::infinity();
  auto ring_edges = [&](const Ring2& ring) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector2d& a = ring[i];
      const Eigen::Vector2d ab = ring[(i + 1) % ring.size()] - a;
      const double length2 = ab.squaredNorm();
      const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
      best2 = std::min(best2, (a + t * ab - p).squaredNorm());
    }
  };
  ring_edges(polygon.outer_uv);
  for (const auto& hole : polygon.holes_uv) ring_edges(hole);
  return std::sqrt(best2);
}

// Square tiles of the outer ring's uv bounding box whose circumscribed disc meets the polygon.
// Every polygon point lies in some tile, and that tile's disc meets the polygon, so the kept
// tiles cover the polygon, and each holds a polygon point within its radius of its centre.
void add_tiles(const PlanarPolygon& polygon, int index, double piece_radius_m,
               std::vector<Piece>& out) {
  Eigen::AlignedBox2d extent;
  for (const auto& uv : polygon.outer_uv) extent.extend(uv);
  const Eigen::Vector2d size = extent.sizes();
  double edge = piece_radius_m * std::sqrt(2.0);
  const double tiles = std::ceil(size.x() / edge) * std::ceil(size.y() / edge);
  if (tiles > kMaxTilesPerPolygon) edge *= std::sqrt(tiles / kMaxTilesPerPolygon);
  const int nx = std::max(1, static_cast<int>(std::ceil(size.x() / edge)));
  const int ny = std::max(1, static_cast<int>(std::ceil(size.y() / edge)));
  const double half_diagonal = 0.5 * edge * std::sqrt(2.0);
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < ny; ++j) {
      const Eigen::Vector2d center_uv =
          extent.min() + Eigen::Vector2d((i + 0.5) * edge, (j + 0.5) * edge);
      if (distance_to_region(polygon, center_uv) > half_diagonal) continue;
      out.push_back({polygon.frame.lift(center_uv), half_diagonal, index});
    }
  }
}

double median_radius(const std::vector<PlanarPolygon>& polygons) {
  if (polygons.empty()) return 0.0;
  std::vector<double> radii;
  radii.reserve(polygons.size());
  for (const auto& p : polygons) radii.push_back(p.radius);
  const auto middle = radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2);
  std::nth_element(radii.begin(), middle, radii.end());
  return *middle;
}

// Turns the pieces found near a query into the exact, ascending answer. Each piece holds a
// polygon point within its radius r of its centre, at distance d (lower bound) from the query:
// d + r <= R accepts the polygon at once; d <= R + r makes it a candidate for the exact test.
template <class PieceDistance, class ExactDistance>
std::vector<int> select(const std::vector<Piece>& pieces,
                        const std::vector<std::pair<std::size_t, double>>& found,
                        std::size_t n_polygons, double range_m, PieceDistance&& piece_distance,
                        ExactDistance&& exact_distance) {
  enum : std::uint8_t { kUnseen, kCandidate, kAccepted };
  std::vector<std::uint8_t> status(n_polygons, kUnseen);
  std::vector<int> candidates;
  std::vector<int> accepted;
  const double sure_range_m = range_m - 1e-9 * (1.0 + range_m);  // leave ties to the exact test
  for (const auto& [piece_index, distance2] : found) {
    const Piece& piece = pieces[piece_index];
    auto& state = status[static_cast<std::size_t>(piece.polygon)];
    if (state == kAccepted) continue;
    const double d = piece_distance(piece, distance2);
    if (d + piece.radius_m <= sure_range_m) {
      state = kAccepted;
      accepted.push_back(piece.polygon);
    } else if (state == kUnseen && d <= range_m + piece.radius_m + 1e-9) {
      state = kCandidate;
      candidates.push_back(piece.polygon);
    }
  }
  for (const int polygon : candidates) {
    auto& state = status[static_cast<std::size_t>(polygon)];
    if (state == kCandidate && exact_distance(polygon) <= range_m) {
      state = kAccepted;
      accepted.push_back(polygon);
    }
  }
  if (accepted.size() * 16 > n_polygons) {  // many: a scan in order beats sorting
    accepted.clear();
    for (std::size_t i = 0; i < n_polygons; ++i) {
      if (status[i] == kAccepted) accepted.push_back(static_cast<int>(i));
    }
  } else {
    std::sort(accepted.begin(), accepted.end());
  }
  return accepted;
}

}  // namespace

struct PlaneIndex::Impl {
  const PlaneMap& map;
  PieceCloud cloud;
  double max_piece_radius_m = 0.0;
  std::unique_ptr<KdTree> tree;
  Eigen::AlignedBox3d extent;  ///< of every polygon

  explicit Impl(const PlaneMap& m) : map(m) {
    for (const PlanarPolygon& polygon : map.polygons) extent.extend(polygon.bounds);
    const double piece_radius_m = std::max(kMinPieceRadius_m, median_radius(map.polygons));
    for (std::size_t i = 0; i < map.polygons.size(); ++i) {
      const PlanarPolygon& polygon = map.polygons[i];
      const int index = static_cast<int>(i);
      if (polygon.radius <= piece_radius_m || polygon.outer_uv.size() < 3) {
        cloud.pieces.push_back({polygon.centroid, polygon.radius, index});
      } else {
        add_tiles(polygon, index, piece_radius_m, cloud.pieces);
      }
    }
    for (const auto& piece : cloud.pieces) {
      max_piece_radius_m = std::max(max_piece_radius_m, piece.radius_m);
    }
    tree = std::make_unique<KdTree>(3, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  }

  // Every polygon lies within range of a query when every corner of the map's box does: the
  // distance to a point or to a box is convex, so greatest over the map's box at a corner. A
  // building that fits in the sensor's range needs no search.
  template <class Distance>
  bool all_within(double range_m, Distance&& distance) const {
    if (extent.isEmpty()) return false;
    const double sure_range_m = range_m - 1e-9 * (1.0 + range_m);
    for (int c = 0; c < 8; ++c) {
      if (!(distance(extent.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c))) <=
            sure_range_m)) {
        return false;
      }
    }
    return true;
  }

  std::vector<int> all() const {
    std::vector<int> indices(map.polygons.size());
    std::iota(indices.begin(), indices.end(), 0);
    return indices;
  }

  // Pieces whose centre lies within `radius_m` of `center` (a little more, never less).
  std::vector<std::pair<std::size_t, double>> pieces_near(const Eigen::Vector3d& center,
                                                          double radius_m) const {
    std::vector<std::pair<std::size_t, double>> found;
    if (cloud.pieces.empty()) return found;
    const double padded = radius_m * (1.0 + 1e-9) + 1e-9;
    tree->radiusSearch(center.data(), padded * padded, found,
                       nanoflann::SearchParams(32, 0, false));
    return found;
  }
};

PlaneIndex::PlaneIndex(const PlaneMap& map) : impl_(std::make_unique<Impl>(map)) {}
PlaneIndex::~PlaneIndex() = default;
PlaneIndex::PlaneIndex(PlaneIndex&&) noexcept = default;
PlaneIndex& PlaneIndex::operator=(PlaneIndex&&) noexcept = default;

std::vector<int> PlaneIndex::within(const Eigen::Vector3d& point, double range_m) const {
  if (!(range_m >= 0.0) || !point.allFinite()) return {};
  if (impl_->all_within(range_m, [&](const Eigen::Vector3d& p) { return (p - point).norm(); })) {
    return impl_->all();
  }
  const auto& polygons = impl_->map.polygons;
  return select(
      impl_->cloud.pieces, impl_->pieces_near(point, range_m + impl_->max_piece_radius_m),
      polygons.size(), range_m, [](const Piece&, double distance2) { return std::sqrt(distance2); },
      [&](int index) {
        return (closest_point(polygons[static_cast<std::size_t>(index)], point) - point).norm();
      });
}

std::vector<int> PlaneIndex::within(const Eigen::AlignedBox3d& box, double range_m) const {
  if (!(range_m >= 0.0) || box.isEmpty() || !box.min().allFinite() || !box.max().allFinite()) {
    return {};
  }
  if (impl_->all_within(range_m,
                         [&](const Eigen::Vector3d& p) { return box.exteriorDistance(p); })) {
    return impl_->all();
  }
  const auto& polygons = impl_->map.polygons;
  const double half_diagonal = 0.5 * box.diagonal().norm();
  return select(
      impl_->cloud.pieces,
      impl_->pieces_near(box.center(), half_diagonal + range_m + impl_->max_piece_radius_m),
      polygons.size(), range_m,
      [&](const Piece& piece, double) { return box.exteriorDistance(piece.center); },
      [&](int index) { return distance_to_box(polygons[static_cast<std::size_t>(index)], box); });
}

}  // namespace conicloc::maps
