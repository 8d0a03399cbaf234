#include "localizer/conic/conic_scan_predictor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "localizer/conic/polygon_arcs.hpp"
#include "localizer/conic/ring_envelope.hpp"

namespace conicloc::localizer {
namespace {

// Elevation band [lo, hi] (radians, from the sensor origin) that holds every point of a sphere
// seen from any apex (0, 0, o) with |o| ≤ max_offset; false when the sphere holds an apex.
bool elevation_band(const PredictionWorkspace::SensorPolygon& polygon, double max_offset_m,
                    double& lo, double& hi) {
  const double x = polygon.centre[0], y = polygon.centre[1], z = polygon.centre[2];
  const double distance = std::sqrt(x * x + y * y + z * z);
  const double radius = polygon.radius + max_offset_m;  // apex shift ⊂ a bigger sphere
  if (!(distance > radius * (1.0 + 1e-9) + 1e-9)) return false;
  const double centre = std::atan2(z, std::hypot(x, y));
  const double half = std::asin(radius / distance) + 1e-9;
  lo = centre - half;
  hi = centre + half;
  return true;
}

// Whether the arcs already clipped for `ring` hide polygon p (occlusion_bins.hpp). Its nearest
// point along the ring's rays is at least the larger of two bounds: the bounding sphere's, and
// the plane's: a ray d(θ) = (cos φ cos θ, cos φ sin θ, sin φ) from the apex a meets n·x + D = 0
// at r = |n·a + D| / |n·d(θ)|, with |n·d(θ)| ≤ cos φ |n_xy| + |sin φ| |n_z|.
// [first, end): the polygon's outer-ring vertices in the workspace.
bool hidden(const RingGeometry& ring, std::size_t p, std::size_t first, std::size_t end,
            PredictionWorkspace& workspace) {
  const auto& polygon = workspace.polygons[p];
  const double slope = ring.cos_elevation * workspace.normal_xy[p] +
                       std::abs(ring.sin_elevation * polygon.normal[2]);
  const double apex_distance =
      std::abs(polygon.normal[2] * ring.vertical_offset_m + polygon.offset);
  const double nearest =
      std::max(workspace.nearest_m[p], slope > 0.0 ? apex_distance / slope : 0.0);
  if (!workspace.span_known[p]) {
    workspace.spans[p] =
        polygon_azimuth_span(&workspace.vertex_x[first], &workspace.vertex_y[first], end - first);
    workspace.span_known[p] = 1;
  }
  return workspace.occlusion.hides(workspace.spans[p], nearest);
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
    : map_(map), rings_(ring_geometry(calibration)), config_(config), max_range_m_(max_range_m) {
  all_polygons_.resize(map.polygons.size());
  std::iota(all_polygons_.begin(), all_polygons_.end(), 0);
}

void ConicScanPredictor::predict(const Pose3& T_map_sensor, PredictedScan& out) const {
  predict(T_map_sensor, all_polygons_, out);
}

void ConicScanPredictor::predict(const Pose3& T_map_sensor, std::span<const int> candidate_polygons,
                                 PredictedScan& out) const {
  PredictionWorkspace& workspace = out.workspace_;
  workspace.polygons.clear();
  workspace.vertex_x.clear();
  workspace.vertex_y.clear();
  workspace.vertex_z.clear();
  workspace.ring_begin.clear();
  out.polygons_considered = candidate_polygons.size();
  out.polygons_outside_field_of_view = 0;
  for (const int index : candidate_polygons) {
    const maps::PlanarPolygon& polygon = map_.polygons[static_cast<std::size_t>(index)];
    add_sensor_polygon(polygon, index, T_map_sensor, workspace);
  }

  double max_offset_m = 0.0;
  for (const RingGeometry& ring : rings_) {
    max_offset_m = std::max(max_offset_m, std::abs(ring.vertical_offset_m));
  }
  const double lo_elevation = rings_.empty() ? 0.0 : rings_.front().elevation_rad;
  const double hi_elevation = rings_.empty() ? 0.0 : rings_.back().elevation_rad;

  out.rings.resize(rings_.size());
  std::vector<PredictionWorkspace::Arc>& arcs = workspace.arcs;
  // Elevation band per polygon (bounding sphere), so a ring skips polygons it cannot reach.
  std::vector<double>& bands = workspace.bands;
  bands.resize(2 * workspace.polygons.size());
  for (std::size_t p = 0; p < workspace.polygons.size(); ++p) {
    double lo = -10.0, hi = 10.0;
    if (!elevation_band(workspace.polygons[p], max_offset_m, lo, hi)) lo = -10.0, hi = 10.0;
    bands[2 * p] = lo;
    bands[2 * p + 1] = hi;
    if (hi < lo_elevation || lo > hi_elevation) ++out.polygons_outside_field_of_view;
  }

  // Front to back: by a lower bound on the distance of each polygon's nearest point from any
  // apex, max(|centre| − radius − max|o|, plane distance − max|o|).
  const std::size_t count = workspace.polygons.size();
  std::vector<int>& order = workspace.front_to_back;
  order.resize(count);
  std::iota(order.begin(), order.end(), 0);
  out.ring_polygons_occluded = 0;
  if (config_.skip_occluded) {
    workspace.nearest_m.resize(count);
    workspace.normal_xy.resize(count);
    workspace.spans.resize(count);
    workspace.span_known.assign(count, 0);
    for (std::size_t p = 0; p < count; ++p) {
      const auto& polygon = workspace.polygons[p];
      const double* c = polygon.centre;
      const double sphere = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) - polygon.radius;
      workspace.nearest_m[p] = std::max(sphere, std::abs(polygon.offset)) - max_offset_m;
      workspace.normal_xy[p] = std::hypot(polygon.normal[0], polygon.normal[1]);
    }
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return workspace.nearest_m[static_cast<std::size_t>(a)] <
             workspace.nearest_m[static_cast<std::size_t>(b)];
    });
  }

  for (std::size_t k = 0; k < rings_.size(); ++k) {
    const RingGeometry& ring = rings_[k];
    arcs.clear();
    if (config_.skip_occluded) workspace.occlusion.reset();
    for (const int p_index : order) {
      const auto p = static_cast<std::size_t>(p_index);
      if (ring.elevation_rad < bands[2 * p] || ring.elevation_rad > bands[2 * p + 1]) continue;
      const auto& polygon = workspace.polygons[p];
      const std::size_t first = workspace.ring_begin[polygon.ring_entry_begin];
      const std::size_t end = workspace.ring_begin[polygon.ring_entry_begin + 1];
      if (config_.skip_occluded && !arcs.empty() && hidden(ring, p, first, end, workspace)) {
        ++out.ring_polygons_occluded;
        continue;
      }
      if (config_.reject_by_elevation &&
          !ring_cuts_polygon(ring, &workspace.vertex_x[first], &workspace.vertex_y[first],
                             &workspace.vertex_z[first], end - first)) {
        continue;
      }
      const std::size_t before = arcs.size();
      append_polygon_arcs(ring, polygon, map_.polygons[static_cast<std::size_t>(polygon.polygon)],
                          workspace, arcs,
                          config_.classify_by_crossing_parity ? ArcClassification::kCrossingParity
                                                              : ArcClassification::kMidpointTests);
      if (config_.skip_occluded) {
        for (std::size_t i = before; i < arcs.size(); ++i) {
          const auto& arc = arcs[i];
          workspace.occlusion.cover(arc.begin_rad, arc.end_rad, arc.a, arc.b, arc.c);
        }
      }
    }
    PredictedRing& predicted = out.rings[k];
    build_ring_envelope(arcs, workspace, predicted);
    predicted.min_inverse_range = 1.0 / max_range_m_;
    predicted.max_inverse_range = 1.0 / config_.min_range_m;
  }
}

}  // namespace conicloc::localizer
