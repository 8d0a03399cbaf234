#include "localizer/filter/plan_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <string>
#include <tuple>
#include <unordered_set>
#include <utility>
#include <vector>

#include "localizer/conic/pose.hpp"
#include "maps/planar_polygon.hpp"
#include "maps/polygon_section.hpp"
#include "parallel/parallel_for.hpp"

namespace conicloc::localizer {

namespace {

/// A node of the search: translations [i, i + 2^level) × [j, j + 2^level) (cells of the field) at
/// one storey and yaw (the task), and the bound Σ_p L_level(c_p + (i, j)) on their scores — an
/// integer, so that comparisons are exact; at level 0 the score itself.
struct Node {
  int bound = 0;
  int level = 0;
  int i = 0;
  int j = 0;
  std::uint32_t task = 0;
};

/// The queue's order: the highest bound first; among equal bounds the coarser node (one that may
/// hold a leaf as good as a leaf beside it is opened first), then a fixed order. A leaf then
/// leaves the queue only when every leaf scoring as much is in it, so the leaves come out in one
/// order, (score, then task, i, j), whatever was expanded when: the candidates do not depend on
/// how many nodes are expanded at once.
struct LowerPriority {
  bool operator()(const Node& a, const Node& b) const {
    return std::make_tuple(a.bound, a.level, -static_cast<std::int64_t>(a.task), -a.i, -a.j) <
           std::make_tuple(b.bound, b.level, -static_cast<std::int64_t>(b.task), -b.i, -b.j);
  }
};

/// The ceiling's height over the floor under most of the navigable floor area: the
/// area-weighted median over the cells (a door's cell, low and small, or a stair's, does not set
/// it for the building); +∞ when the map gives no cell a ceiling.
double typical_ceiling_height(const maps::PlaneMap& map) {
  std::vector<std::pair<double, double>> heights;  // (height, area)
  double total = 0.0;
  for (const maps::Cell& cell : map.cells) {
    const double area = std::abs(maps::signed_area(cell.footprint));
    if (!cell.navigable || !(cell.ceiling_z > cell.floor_z) || !(area > 0.0)) continue;
    heights.emplace_back(cell.ceiling_z - cell.floor_z, area);
    total += area;
  }
  if (heights.empty()) return std::numeric_limits<double>::infinity();
  std::sort(heights.begin(), heights.end());
  double cumulative = 0.0;
  for (const auto& [height, area] : heights) {
    cumulative += area;
    if (cumulative >= 0.5 * total) return height;
  }
  return heights.back().first;
}

}  // namespace

PlanSearch::PlanSearch(const maps::PlaneMap& map, const FreeSpace& free_space,
                       double height_above_floor_m, const PlanSearchConfig& config)
    : map_(map),
      free_space_(free_space),
      config_(config),
      floor_below_m_(height_above_floor_m),
      ceiling_above_m_(typical_ceiling_height(map) - height_above_floor_m) {
  // Storeys as the map has them; a map without any is one storey at its lowest navigable floor.
  std::vector<std::pair<int, double>> storeys;
  for (std::size_t s = 0; s < map.storeys.size(); ++s)
    storeys.emplace_back(static_cast<int>(s), map.storeys[s].floor_z);
  if (storeys.empty()) {
    double lowest = std::numeric_limits<double>::infinity();
    for (const maps::Cell& cell : map.cells)
      if (cell.navigable) lowest = std::min(lowest, cell.floor_z);
    if (std::isfinite(lowest)) storeys.emplace_back(-1, lowest);
  }
  if (!(config.resolution_m > 0.0) || !std::isfinite(config.resolution_m) ||
      !(config.max_range_m >= 0.0) || !std::isfinite(config.max_range_m))
    throw std::invalid_argument("plan search: resolution_m must be positive and max_range_m " +
                                std::string("non-negative, both finite"));
  const double margin = 3.0 * config.field_sigma_m + config.resolution_m;
  // Cells of 0 around each field, as far as a return the search matches lies from the sensor
  // (max_range_m, and a cell for the rounding either way): a translation searched stands in the
  // extent, so every cell a bound sums lies in the grid and needs no check.
  const int padding_cells =
      static_cast<int>(std::ceil(config.max_range_m / config.resolution_m)) + 2;
  for (const auto& [storey, floor_z] : storeys) {
    const auto on_storey = [storey = storey](int cell_storey) {
      return storey < 0 || cell_storey == storey;
    };
    Eigen::AlignedBox2d extent;
    double top_floor_z = floor_z;
    for (const maps::Cell& cell : map.cells) {
      if (!cell.navigable || !on_storey(cell.storey)) continue;
      extent.extend(Eigen::AlignedBox2d(cell.bounds.min().head<2>(), cell.bounds.max().head<2>()));
      top_floor_z = std::max(top_floor_z, cell.floor_z);
    }
    if (extent.isEmpty()) continue;
    const Eigen::AlignedBox2d field_extent(extent.min() - Eigen::Vector2d::Constant(margin),
                                           extent.max() + Eigen::Vector2d::Constant(margin));
    // The walls as the sensor's rings see them from the rooms they bound: each cut at the
    // sensor's height over its own cell's floor. A storey's floor is not flat (KU: rooms from
    // −3.9 to −0.9 m on one storey); cut over the storey's lowest floor, the walls of its
    // higher rooms would be missing, and the scan's returns would find no wall there.
    std::vector<maps::SectionSegment> walls;
    for (const maps::PlanarPolygon& polygon : map.polygons) {
      if (polygon.kind != maps::SurfaceKind::Wall || !on_storey(polygon.storey)) continue;
      const double section_z =
          (polygon.cell >= 0 ? map.cells[static_cast<std::size_t>(polygon.cell)].floor_z
                             : floor_z) +
          height_above_floor_m;
      if (polygon.bounds.min().z() > section_z || polygon.bounds.max().z() < section_z) continue;
      for (const maps::SectionSegment& piece : maps::horizontal_section(polygon, section_z))
        walls.push_back(piece);
    }
    StoreyPlan plan{floor_z,
                    top_floor_z,
                    storey,
                    PlanField(walls, field_extent, config.resolution_m, config.field_sigma_m,
                              config.coarsest_level + 1, padding_cells),
                    {},
                    {}};
    const auto cell_of = [&](const Eigen::Vector2d& p) {
      return Eigen::Vector2i(
          static_cast<int>(std::floor((p.x() - plan.field.origin().x()) / config.resolution_m)),
          static_cast<int>(std::floor((p.y() - plan.field.origin().y()) / config.resolution_m)));
    };
    plan.t_min = cell_of(extent.min());
    plan.t_max = cell_of(extent.max());
    storeys_.push_back(std::move(plan));
  }
}

std::vector<Eigen::Vector2d> PlanSearch::search_points(const sensor::Scan& scan) const {
  // The rings within max_elevation_rad of horizontal; where none is, the one nearest to it.
  double nearest = std::numeric_limits<double>::infinity();
  for (const sensor::RingScan& ring : scan.rings)
    if (!ring.returns.empty()) nearest = std::min(nearest, std::abs(ring.elevation_rad));
  const double max_elevation = std::max(config_.max_elevation_rad, nearest);
  // A return's height over a level sensor, z = r sin φ, within the clearance of the floor
  // (z = −h) or of the ceiling is taken for that surface. The clearance is at most half the way
  // to either, so that a sensor near the floor (a small robot's, 0.2 m up) or the ceiling keeps
  // its level rings, and grows by d·tan(tilt allowance) with the horizontal distance d.
  const double floor_clearance = std::min(config_.surface_clearance_m, 0.5 * floor_below_m_);
  const double ceiling_clearance = std::min(config_.surface_clearance_m, 0.5 * ceiling_above_m_);
  const double tilt_slope = std::tan(config_.tilt_allowance_rad);
  std::vector<Eigen::Vector2d> points;
  std::unordered_set<std::int64_t> occupied;
  for (const sensor::RingScan& ring : scan.rings) {
    if (std::abs(ring.elevation_rad) > max_elevation) continue;
    const double horizontal = std::cos(ring.elevation_rad);
    const double vertical = std::sin(ring.elevation_rad);
    for (const sensor::Return& ret : ring.returns) {
      if (ret.status != sensor::ReturnStatus::Valid) continue;
      const double d = ret.range_m * horizontal;
      if (!(d >= config_.min_range_m && d <= config_.max_range_m)) continue;
      const double z = ret.range_m * vertical;
      const double tilt = d * tilt_slope;
      if (z < floor_clearance + tilt - floor_below_m_ ||
          z > ceiling_above_m_ - (ceiling_clearance + tilt))
        continue;
      const Eigen::Vector2d p(d * std::cos(ret.azimuth_rad), d * std::sin(ret.azimuth_rad));
      const auto key =
          (static_cast<std::int64_t>(std::floor(p.x() / config_.point_spacing_m)) << 32) ^
          static_cast<std::int64_t>(static_cast<std::uint32_t>(
              static_cast<std::int32_t>(std::floor(p.y() / config_.point_spacing_m))));
      if (occupied.insert(key).second) points.push_back(p);
    }
  }
  if (points.size() > config_.max_points) {
    std::vector<Eigen::Vector2d> thinned;
    for (std::size_t k = 0; k < config_.max_points; ++k)
      thinned.push_back(points[k * points.size() / config_.max_points]);
    points = std::move(thinned);
  }
  return points;
}

std::vector<PlanCandidate> PlanSearch::search(const sensor::Scan& scan,
                                              const std::vector<double>& headings,
                                              int threads) const {
  const std::vector<Eigen::Vector2d> points = search_points(scan);
  if (points.empty() || storeys_.empty()) return {};
  // A heading step that moves the farthest return by one cell: atan(resolution / range).
  double reach = 0.0;
  for (const Eigen::Vector2d& p : points) reach = std::max(reach, p.norm());
  const double step = std::atan2(config_.resolution_m, std::max(reach, config_.resolution_m));
  std::vector<double> yaws;
  if (headings.empty()) {
    const int count = static_cast<int>(std::ceil(2.0 * M_PI / step));
    for (int k = 0; k < count; ++k) yaws.push_back(-M_PI + 2.0 * M_PI * k / count);
  } else {
    const int half = static_cast<int>(std::ceil(config_.heading_window_rad / step));
    for (const double heading : headings)
      for (int k = -half; k <= half; ++k) yaws.push_back(angle_difference(heading + k * step, 0.0));
  }

  // Per task (storey × yaw): the cell offset of every return, t + ⌊R(ψ)p / resolution⌋ being the
  // cell it falls in from a sensor at the corner of cell t, as an offset into the storey's field
  // (rows of width w): (⌊q_y / resolution⌋·w + ⌊q_x / resolution⌋). The returns lie within
  // max_range_m, which the fields' padding holds (PlanSearch()).
  const std::size_t tasks = yaws.size() * storeys_.size();
  const std::size_t n = points.size();
  std::vector<std::ptrdiff_t> offsets(tasks * n);
  for (std::size_t t = 0; t < tasks; ++t) {
    const double yaw = yaws[t / storeys_.size()];
    const double c = std::cos(yaw), s = std::sin(yaw);
    const auto width = static_cast<std::ptrdiff_t>(storeys_[t % storeys_.size()].field.width());
    for (std::size_t k = 0; k < n; ++k) {
      const Eigen::Vector2d& p = points[k];
      const Eigen::Vector2d q(c * p.x() - s * p.y(), s * p.x() + c * p.y());
      offsets[t * n + k] =
          static_cast<std::ptrdiff_t>(std::floor(q.y() / config_.resolution_m)) * width +
          static_cast<std::ptrdiff_t>(std::floor(q.x() / config_.resolution_m));
    }
  }
  const auto plan_of = [&](std::uint32_t task) -> const StoreyPlan& {
    return storeys_[task % storeys_.size()];
  };
  const auto bound = [&](std::uint32_t task, int level, int i, int j) {
    const PlanField& field = plan_of(task).field;
    const std::uint8_t* origin =
        field.cells(level) + static_cast<std::ptrdiff_t>(j) * field.width() + i;
    const std::ptrdiff_t* offset = offsets.data() + task * n;
    int sum = 0;
    for (std::size_t k = 0; k < n; ++k) sum += origin[offset[k]];
    return sum;
  };

  // The roots: every task's translations tiled by nodes of the coarsest level, bounded in
  // parallel (each bound a pure function of its node).
  const int coarsest = std::max(config_.coarsest_level, 0);
  std::vector<Node> roots;
  for (std::uint32_t task = 0; task < tasks; ++task) {
    const StoreyPlan& plan = plan_of(task);
    for (int i = plan.t_min.x(); i <= plan.t_max.x(); i += 1 << coarsest)
      for (int j = plan.t_min.y(); j <= plan.t_max.y(); j += 1 << coarsest)
        roots.push_back({0, coarsest, i, j, task});
  }
  // Nodes bounded in parallel (each bound a pure function of its node); a few inline, where
  // starting a thread would cost more than their sums.
  const int workers = resolve_thread_count(threads);
  const auto bound_all = [&](std::vector<Node>& nodes) {
    constexpr std::size_t kMinParallel = 64;
    parallel_for(nodes.size(), nodes.size() < kMinParallel ? 1 : workers,
                 [&](std::size_t begin, std::size_t end, int /*worker*/) {
                   for (std::size_t r = begin; r < end; ++r)
                     nodes[r].bound = bound(nodes[r].task, nodes[r].level, nodes[r].i, nodes[r].j);
                 });
  };
  bound_all(roots);
  const int min_total =
      static_cast<int>(std::ceil(config_.min_score * 255.0 * static_cast<double>(points.size())));
  std::priority_queue<Node, std::vector<Node>, LowerPriority> queue;
  for (const Node& root : roots)
    if (root.bound >= min_total) queue.push(root);

  // Best first: a leaf popped scores at least every bound left in the queue, so the leaves come
  // out in the order of their scores, and the search ends with the max_candidates-th distinct one.
  // The nodes at the top of the queue down to the first leaf, at most expand_batch of them, are
  // expanded together and their children bounded on the threads. A batch may open nodes that the
  // search one node at a time would have pruned (a child of an earlier node of the batch, not yet
  // in the queue, might have given the first candidate and raised the floor): that costs time,
  // never a candidate, since the leaves come out in one order whatever was opened.
  const double distinct_m = config_.resolution_m * (1 << std::max(config_.distinct_level, 0));
  const std::size_t expand_batch = std::max<std::size_t>(config_.expand_batch, 1);
  std::vector<PlanCandidate> kept;
  std::vector<std::size_t> kept_storeys;
  std::vector<Node> children;
  int floor_total = min_total;  // raised to min_relative_score of the best once there is one
  while (!queue.empty() && kept.size() < config_.max_candidates) {
    if (queue.top().bound < floor_total) break;
    if (queue.top().level > 0) {
      children.clear();
      for (std::size_t opened = 0; opened < expand_batch && !queue.empty() &&
                                   queue.top().level > 0 && queue.top().bound >= floor_total;
           ++opened) {
        const Node node = queue.top();
        queue.pop();
        const StoreyPlan& plan = plan_of(node.task);
        const int half = 1 << (node.level - 1);
        for (const auto& [di, dj] :
             {std::pair{0, 0}, std::pair{1, 0}, std::pair{0, 1}, std::pair{1, 1}}) {
          const Node child{0, node.level - 1, node.i + di * half, node.j + dj * half, node.task};
          if (child.i <= plan.t_max.x() && child.j <= plan.t_max.y()) children.push_back(child);
        }
      }
      bound_all(children);
      for (const Node& child : children)
        if (child.bound >= floor_total) queue.push(child);
      continue;
    }
    const Node node = queue.top();
    queue.pop();
    const StoreyPlan& plan = plan_of(node.task);
    PlanCandidate candidate;
    const Eigen::Vector2d xy =
        plan.field.origin() + config_.resolution_m * Eigen::Vector2d(node.i, node.j);
    candidate.x = xy.x();
    candidate.y = xy.y();
    candidate.yaw = yaws[node.task / storeys_.size()];
    candidate.score = node.bound / (255.0 * static_cast<double>(points.size()));
    const std::size_t storey = node.task % storeys_.size();
    bool duplicate = false;
    for (std::size_t k = 0; k < kept.size() && !duplicate; ++k)
      duplicate = kept_storeys[k] == storey &&
                  std::hypot(kept[k].x - candidate.x, kept[k].y - candidate.y) < distinct_m &&
                  std::abs(angle_difference(kept[k].yaw, candidate.yaw)) < config_.distinct_yaw_rad;
    if (duplicate) continue;
    // On the storey's free floor only: the sensor stands in a navigable cell of it. Its floor
    // may lie well above the storey's lowest one (KU): asked from the storey's highest floor,
    // the free space answers with the highest floor under the point, then the storey is checked.
    candidate.cell = free_space_.cell_at(xy.x(), xy.y(), plan.top_floor_z);
    if (candidate.cell < 0 ||
        (plan.storey >= 0 &&
         map_.cells[static_cast<std::size_t>(candidate.cell)].storey != plan.storey))
      continue;
    candidate.floor_z = free_space_.floor_z_at(candidate.cell, xy.x(), xy.y(), plan.top_floor_z);
    kept.push_back(candidate);
    kept_storeys.push_back(storey);
    if (kept.size() == 1)
      floor_total =
          std::max(min_total, static_cast<int>(std::ceil(config_.min_relative_score * node.bound)));
  }
  return kept;
}

std::size_t PlanSearch::memory_bytes() const {
  std::size_t bytes = 0;
  for (const StoreyPlan& plan : storeys_) bytes += plan.field.memory_bytes();
  return bytes;
}

}  // namespace conicloc::localizer
