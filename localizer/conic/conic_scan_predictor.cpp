#include "localizer/conic/conic_scan_predictor.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <numeric>

#include "localizer/conic/polygon_arcs.hpp"
#include "localizer/conic/ring_envelope.hpp"

namespace conicloc::localizer {
namespace {

// How far a ray of elevation φ from an apex at height o travels before it reaches the height
// range [z_low, z_high]: its height is o + r sin φ, so r ≥ (z_low − o) / sin φ above the apex and
// (o − z_high) / (−sin φ) below it; 0 when the apex's height is in the range or the ray is level.
double height_reach_m(double sin_elevation, double apex_z, double z_low, double z_high) {
  if (sin_elevation > 0.0 && z_low > apex_z) return (z_low - apex_z) / sin_elevation;
  if (sin_elevation < 0.0 && z_high < apex_z) return (apex_z - z_high) / -sin_elevation;
  return 0.0;
}

// False when no ray of a ring of elevation φ from an apex at height o can reach the height range
// [z_low, z_high]: the range wholly above the apex for a level or downward ring, or wholly
// below it for a level or upward one (a ray's height o + r sin φ only moves away from it).
bool ring_reaches_heights(double sin_elevation, double apex_z, double z_low, double z_high) {
  const double margin = 1e-9 * (1.0 + std::abs(z_low) + std::abs(z_high));
  if (sin_elevation <= 0.0 && z_low > apex_z + margin) return false;
  if (sin_elevation >= 0.0 && z_high < apex_z - margin) return false;
  return true;
}

// A lower bound on the range at which the rays of `ring` meet polygon p: the largest of three
// bounds: the bounding sphere's; the plane's: a ray d(θ) = (cos φ cos θ, cos φ sin θ, sin φ) from
// the apex a meets n·x + D = 0 at r = |n·a + D| / |n·d(θ)|, with |n·d(θ)| ≤ cos φ |n_xy| +
// |sin φ| |n_z|; and the height's (height_reach_m: the rooms of another storey lie beyond the
// floor or ceiling the ring crosses first).
double nearest_range_m(const RingGeometry& ring, std::size_t p,
                       const PredictionWorkspace& workspace) {
  const auto& polygon = workspace.polygons[p];
  const double slope = ring.cos_elevation * workspace.normal_xy[p] +
                       std::abs(ring.sin_elevation * polygon.normal[2]);
  const double apex_distance =
      std::abs(polygon.normal[2] * ring.vertical_offset_m + polygon.offset);
  return std::max({workspace.nearest_m[p], slope > 0.0 ? apex_distance / slope : 0.0,
                   height_reach_m(ring.sin_elevation, ring.vertical_offset_m, workspace.z_low[p],
                                  workspace.z_high[p])});
}

// Whether the arcs already clipped for `ring` hide polygon p (occlusion_bins.hpp), whose nearest
// point along the ring's rays is at least `nearest_m`. [first, end): the polygon's outer-ring
// vertices in the workspace.
bool hidden(std::size_t p, double nearest_m, std::size_t first, std::size_t end,
            PredictionWorkspace& workspace) {
  if (!workspace.span_known[p]) {
    workspace.spans[p] =
        polygon_azimuth_span(&workspace.vertex_x[first], &workspace.vertex_y[first], end - first);
    workspace.span_known[p] = 1;
  }
  return workspace.occlusion.hides(workspace.spans[p], nearest_m);
}

}  // namespace

bool ring_cuts_polygon(const RingGeometry& ring, const double* x, const double* y, const double* z,
                       std::size_t count) {
  if (count == 0) return false;
  const double c = ring.cos_elevation, s = ring.sin_elevation, o = ring.vertical_offset_m;
  double g_min = std::numeric_limits<double>::infinity(), g_max = -g_min;
  double h_min = g_min, h_max = -g_min;  // z − o
  double extent = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double rho = std::sqrt(x[i] * x[i] + y[i] * y[i]);
    const double h = z[i] - o;
    const double g = h * c - rho * s;
    g_min = std::min(g_min, g);
    g_max = std::max(g_max, g);
    h_min = std::min(h_min, h);
    h_max = std::max(h_max, h);
    extent = std::max(extent, rho + std::abs(h));
  }
  const double margin = 1e-9 * (1.0 + extent);
  if (s >= 0.0 && (g_min > margin || h_max < -margin)) return false;
  if (s <= 0.0 && (g_max < -margin || h_min > margin)) return false;
  return true;
}

ConicScanPredictor::ConicScanPredictor(const maps::PlaneMap& map,
                                       const sensor::LaserCalibration& calibration,
                                       PredictorConfig config, double max_range_m)
    : map_(map),
      groups_(map),
      rings_(ring_geometry(calibration)),
      config_(config),
      max_range_m_(max_range_m),
      beyond_range_m_(max_range_m + config.beyond_range_margin_m) {
  for (const RingGeometry& ring : rings_) {
    max_offset_m_ = std::max(max_offset_m_, std::abs(ring.vertical_offset_m));
  }
  if (!rings_.empty()) {
    lo_elevation_rad_ = rings_.front().elevation_rad;
    hi_elevation_rad_ = rings_.back().elevation_rad;
  }
  sin_lo_elevation_ = std::sin(lo_elevation_rad_);
  sin_hi_elevation_ = std::sin(hi_elevation_rad_);
  all_polygons_.resize(map.polygons.size());
  std::iota(all_polygons_.begin(), all_polygons_.end(), 0);
  all_rings_.resize(rings_.size());
  std::iota(all_rings_.begin(), all_rings_.end(), 0);
}

void ConicScanPredictor::predict(const Pose3& T_map_sensor, PredictedScan& out) const {
  predict(T_map_sensor, all_polygons_, out);
}

void ConicScanPredictor::predict(const Pose3& T_map_sensor, std::span<const int> candidate_polygons,
                                 PredictedScan& out) const {
  predict(T_map_sensor, candidate_polygons, all_rings_, out);
}

void ConicScanPredictor::predict(const Pose3& T_map_sensor, std::span<const int> candidate_polygons,
                                 std::span<const int> rings, PredictedScan& out) const {
  PredictionWorkspace& workspace = out.workspace_;
  workspace.polygons.clear();
  workspace.vertex_x.clear();
  workspace.vertex_y.clear();
  workspace.vertex_z.clear();
  workspace.ring_begin.clear();
  workspace.bands.clear();
  workspace.nearest_m.clear();
  workspace.normal_xy.clear();
  workspace.z_low.clear();
  workspace.z_high.clear();
  workspace.spans.clear();
  workspace.span_known.clear();
  workspace.front_to_back.clear();
  out.polygons_considered = candidate_polygons.size();
  out.polygons_outside_field_of_view = 0;
  out.ring_polygons_occluded = 0;
  out.ring_polygons_beyond_range = 0;
  out.ring_polygons_clipped = 0;

  assert(std::is_sorted(rings.begin(), rings.end()) &&
         (rings.empty() || (rings.front() >= 0 && rings.back() < static_cast<int>(rings_.size()))));
  select_groups(T_map_sensor, candidate_polygons, rings.size(), out);
  out.rings.resize(rings_.size());
  std::size_t next = 0;  // in `rings`
  for (std::size_t k = 0; k < rings_.size(); ++k) {
    while (next < rings.size() && rings[next] < static_cast<int>(k)) ++next;
    if (next < rings.size() && rings[next] == static_cast<int>(k)) {
      predict_ring(k, T_map_sensor, out);
    } else {  // one gap, as a ring that meets nothing
      workspace.arcs.clear();
      build_ring_envelope(workspace.arcs, workspace, out.rings[k]);
      out.rings[k].min_inverse_range = 1.0 / max_range_m_;
      out.rings[k].max_inverse_range = 1.0 / config_.min_range_m;
    }
  }
  out.polygons_prepared = workspace.polygons.size();
}

double ConicScanPredictor::reach_any_ring(double low, double high) const {
  // The height reach over the steepest ring towards [low, high] from the farthest apex
  // (height_reach_m grows as |sin φ| shrinks and as the apex moves away).
  return std::max(
      hi_elevation_rad_ > 0.0 ? height_reach_m(sin_hi_elevation_, max_offset_m_, low, high) : 0.0,
      lo_elevation_rad_ < 0.0 ? height_reach_m(sin_lo_elevation_, -max_offset_m_, low, high) : 0.0);
}

void ConicScanPredictor::select_groups(const Pose3& T_map_sensor,
                                       std::span<const int> candidate_polygons,
                                       std::size_t ring_count, PredictedScan& out) const {
  PredictionWorkspace& workspace = out.workspace_;
  // The candidates by group, a counting sort.
  std::vector<std::size_t>& start = workspace.group_start;
  start.assign(groups_.size() + 1, 0);
  for (const int index : candidate_polygons)
    ++start[static_cast<std::size_t>(groups_.group_of(index)) + 1];
  for (std::size_t g = 0; g < groups_.size(); ++g) start[g + 1] += start[g];
  workspace.group_members.resize(candidate_polygons.size());
  workspace.group_fill.assign(start.begin(), start.end() - 1);
  for (const int index : candidate_polygons) {
    const auto g = static_cast<std::size_t>(groups_.group_of(index));
    workspace.group_members[workspace.group_fill[g]++] = index;
  }
  std::vector<PredictionWorkspace::Group>& groups = workspace.groups;
  groups.clear();
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    if (start[g] == start[g + 1]) continue;
    const SensorBox view =
        sensor_box(groups_.box(static_cast<int>(g)), T_map_sensor, max_offset_m_);
    if (config_.skip_occluded &&
        (view.elevation_high < lo_elevation_rad_ || view.elevation_low > hi_elevation_rad_)) {
      out.polygons_outside_field_of_view += start[g + 1] - start[g];
      continue;
    }
    const double nearest_m = std::max(view.nearest_m, reach_any_ring(view.z_low, view.z_high));
    // Every ray meets the box beyond the sensor's range, where a return reads as none (each ring
    // counts its members as left out).
    if (config_.skip_occluded && nearest_m > beyond_range_m_) {
      out.ring_polygons_beyond_range += (start[g + 1] - start[g]) * ring_count;
      continue;
    }
    groups.push_back({.members_begin = start[g],
                      .members_end = start[g + 1],
                      .view = view,
                      .nearest_m = nearest_m});
  }
  if (config_.skip_occluded) {
    std::sort(groups.begin(), groups.end(),
              [](const auto& a, const auto& b) { return a.nearest_m < b.nearest_m; });
  }
}

void ConicScanPredictor::prepare_group(PredictionWorkspace::Group& group, const Pose3& T_map_sensor,
                                       PredictedScan& out) const {
  PredictionWorkspace& workspace = out.workspace_;
  const std::size_t begin = workspace.polygons.size();
  for (std::size_t m = group.members_begin; m < group.members_end; ++m) {
    const int index = workspace.group_members[m];
    add_sensor_polygon(map_.polygons[static_cast<std::size_t>(index)], index, T_map_sensor,
                       workspace);
  }
  for (std::size_t p = begin; p < workspace.polygons.size(); ++p) {
    const auto& polygon = workspace.polygons[p];
    double lo = -10.0, hi = 10.0;
    const Eigen::Vector3d centre(polygon.centre[0], polygon.centre[1], polygon.centre[2]);
    if (!sphere_elevation_band(centre, polygon.radius, max_offset_m_, lo, hi)) {
      lo = -10.0, hi = 10.0;
    }
    workspace.bands.push_back(lo);
    workspace.bands.push_back(hi);
    if (hi < lo_elevation_rad_ || lo > hi_elevation_rad_) ++out.polygons_outside_field_of_view;
    const double* c = polygon.centre;
    const double sphere = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) - polygon.radius;
    const std::size_t first = workspace.ring_begin[polygon.ring_entry_begin];
    const std::size_t end = workspace.ring_begin[polygon.ring_entry_begin + 1];
    const auto [low, high] =
        std::minmax_element(workspace.vertex_z.begin() + first, workspace.vertex_z.begin() + end);
    workspace.z_low.push_back(*low);
    workspace.z_high.push_back(*high);
    workspace.nearest_m.push_back(std::max(
        std::max(sphere, std::abs(polygon.offset)) - max_offset_m_, reach_any_ring(*low, *high)));
    workspace.normal_xy.push_back(
        std::sqrt(polygon.normal[0] * polygon.normal[0] + polygon.normal[1] * polygon.normal[1]));
    workspace.spans.emplace_back();
    workspace.span_known.push_back(0);
    workspace.front_to_back.push_back(static_cast<int>(p));
  }
  group.order_begin = begin;
  group.order_end = workspace.front_to_back.size();
  if (config_.skip_occluded) {
    std::sort(workspace.front_to_back.begin() + static_cast<std::ptrdiff_t>(begin),
              workspace.front_to_back.end(), [&](int a, int b) {
                return workspace.nearest_m[static_cast<std::size_t>(a)] <
                       workspace.nearest_m[static_cast<std::size_t>(b)];
              });
  }
  group.prepared = true;
}

void ConicScanPredictor::visit_group(const RingGeometry& ring, PredictionWorkspace::Group& group,
                                     double nearest_m, const Pose3& T_map_sensor,
                                     PredictedScan& out) const {
  PredictionWorkspace& workspace = out.workspace_;
  std::vector<PredictionWorkspace::Arc>& arcs = workspace.arcs;
  if (config_.skip_occluded) {
    if (nearest_m > beyond_range_m_) {
      out.ring_polygons_beyond_range += group.members_end - group.members_begin;
      return;
    }
    if (!arcs.empty() && workspace.occlusion.hides(group.view.span, nearest_m)) {
      out.ring_polygons_occluded += group.members_end - group.members_begin;
      return;
    }
  }
  if (!group.prepared) prepare_group(group, T_map_sensor, out);
  for (std::size_t i = group.order_begin; i < group.order_end; ++i) {
    const auto p = static_cast<std::size_t>(workspace.front_to_back[i]);
    if (ring.elevation_rad < workspace.bands[2 * p] ||
        ring.elevation_rad > workspace.bands[2 * p + 1]) {
      continue;
    }
    const auto& polygon = workspace.polygons[p];
    const std::size_t first = workspace.ring_begin[polygon.ring_entry_begin];
    const std::size_t end = workspace.ring_begin[polygon.ring_entry_begin + 1];
    if (config_.skip_occluded) {
      const double polygon_nearest_m = nearest_range_m(ring, p, workspace);
      if (polygon_nearest_m > beyond_range_m_) {
        ++out.ring_polygons_beyond_range;
        continue;
      }
      if (!arcs.empty() && hidden(p, polygon_nearest_m, first, end, workspace)) {
        ++out.ring_polygons_occluded;
        continue;
      }
    }
    if (config_.reject_by_elevation &&
        !ring_cuts_polygon(ring, &workspace.vertex_x[first], &workspace.vertex_y[first],
                           &workspace.vertex_z[first], end - first)) {
      continue;
    }
    ++out.ring_polygons_clipped;
    const std::size_t before = arcs.size();
    append_polygon_arcs(ring, polygon, map_.polygons[static_cast<std::size_t>(polygon.polygon)],
                        workspace, arcs,
                        config_.classify_by_crossing_parity ? ArcClassification::kCrossingParity
                                                            : ArcClassification::kMidpointTests);
    if (config_.skip_occluded) {
      for (std::size_t a = before; a < arcs.size(); ++a) {
        const auto& arc = arcs[a];
        workspace.occlusion.cover(arc.begin_rad, arc.end_rad, arc.a, arc.b, arc.c);
      }
    }
  }
}

void ConicScanPredictor::predict_ring(std::size_t k, const Pose3& T_map_sensor,
                                      PredictedScan& out) const {
  PredictionWorkspace& workspace = out.workspace_;
  const RingGeometry& ring = rings_[k];
  workspace.arcs.clear();
  if (config_.skip_occluded) workspace.occlusion.reset();
  // The groups front to back by nearest_m, except those this ring reaches only farther, past the
  // heights in between (the storeys above and below): they come last, front to back by that
  // reach, once the nearer arcs can hide them.
  workspace.deferred.clear();
  for (std::size_t g = 0; g < workspace.groups.size(); ++g) {
    PredictionWorkspace::Group& group = workspace.groups[g];
    if (!config_.skip_occluded) {
      visit_group(ring, group, 0.0, T_map_sensor, out);
      continue;
    }
    if (ring.elevation_rad < group.view.elevation_low ||
        ring.elevation_rad > group.view.elevation_high ||
        !ring_reaches_heights(ring.sin_elevation, ring.vertical_offset_m, group.view.z_low,
                              group.view.z_high)) {
      continue;
    }
    const double reach_m = height_reach_m(ring.sin_elevation, ring.vertical_offset_m,
                                          group.view.z_low, group.view.z_high);
    if (reach_m > group.nearest_m) {
      workspace.deferred.emplace_back(reach_m, g);
    } else {
      visit_group(ring, group, group.nearest_m, T_map_sensor, out);
    }
  }
  std::sort(workspace.deferred.begin(), workspace.deferred.end());
  for (const auto& [reach_m, g] : workspace.deferred) {
    visit_group(ring, workspace.groups[g], reach_m, T_map_sensor, out);
  }
  PredictedRing& predicted = out.rings[k];
  build_ring_envelope(workspace.arcs, workspace, predicted);
  predicted.min_inverse_range = 1.0 / max_range_m_;
  predicted.max_inverse_range = 1.0 / config_.min_range_m;
}

}  // namespace conicloc::localizer
