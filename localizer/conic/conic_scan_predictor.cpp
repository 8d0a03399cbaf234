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

  for (std::size_t k = 0; k < rings_.size(); ++k) {
    const RingGeometry& ring = rings_[k];
    arcs.clear();
    for (std::size_t p = 0; p < workspace.polygons.size(); ++p) {
      if (ring.elevation_rad < bands[2 * p] || ring.elevation_rad > bands[2 * p + 1]) continue;
      const auto& polygon = workspace.polygons[p];
      if (config_.reject_by_elevation) {
        const std::size_t first = workspace.ring_begin[polygon.ring_entry_begin];
        const std::size_t end = workspace.ring_begin[polygon.ring_entry_begin + 1];
        if (!ring_cuts_polygon(ring, &workspace.vertex_x[first], &workspace.vertex_y[first],
                               &workspace.vertex_z[first], end - first)) {
          continue;
        }
      }
      append_polygon_arcs(ring, polygon, map_.polygons[static_cast<std::size_t>(polygon.polygon)],
                          workspace, arcs,
                          config_.classify_by_crossing_parity ? ArcClassification::kCrossingParity
                                                              : ArcClassification::kMidpointTests);
    }
    PredictedRing& predicted = out.rings[k];
    build_ring_envelope(arcs, workspace, predicted);
    predicted.min_inverse_range = 1.0 / max_range_m_;
    predicted.max_inverse_range = 1.0 / config_.min_range_m;
  }
}

}  // namespace conicloc::localizer
