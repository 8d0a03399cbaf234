#pragma once
// ConicScanPredictor: the scan a LiDAR at a pose sees in a PlaneMap, ring by ring, as
// piecewise conics (DESIGN.md "The conic sensor model", "Bounded planes"). For each ring and
// candidate polygon: the ray-form conic of the polygon's plane in the sensor frame, clipped to the
// polygon (outer ring minus holes) as exact azimuth arcs; over all polygons, the nearest positive
// range wins (switch points between two conics in closed form). The per-particle hot path.
//
// Usage (one PredictedScan per thread, reused for every particle):
//   ConicScanPredictor predictor(map, calibration, {});
//   PredictedScan predicted;                       // workspace + result
//   predictor.predict(T_map_sensor, candidates, predicted);
//   predicted.ring(k).evaluate_sorted(samples_k, ranges_k);   // samples: AzimuthSamples per ring

#include <span>
#include <vector>

#include "localizer/conic/polygon_groups.hpp"
#include "localizer/conic/pose.hpp"
#include "localizer/conic/predicted_scan.hpp"
#include "localizer/conic/ring_geometry.hpp"
#include "maps/plane_map.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::localizer {

struct PredictorConfig {
  double min_range_m = 0.3;  ///< VLP-16: closer surfaces block the beam but return nothing
  /// Skip a (ring, polygon) pair when the polygon's outer vertices show it lies wholly on one side
  /// of the ring's half-cone (exact, see ring_cuts_polygon()); off only to measure its gain.
  bool reject_by_elevation = true;
  /// Classify a polygon's azimuth intervals by toggling each vertex ring's inside state at its
  /// edge crossings (one point-in-polygon test per ring and polygon) instead of one test per
  /// interval; the same arcs but for slivers between coincident crossings of two vertex rings
  /// (see append_polygon_arcs()). Off only to measure its gain.
  bool classify_by_crossing_parity = true;
  /// Clip each ring's polygons nearest first and skip those the arcs already clipped hide
  /// (occlusion_bins.hpp) or that lie wholly beyond the sensor's range plus
  /// beyond_range_margin_m along the ring, and leave out whole the groups of polygons
  /// (polygon_groups.hpp) that a ring cannot reach, that lie beyond that range, or whose box such
  /// arcs hide: the same ranges (where coplanar polygons tie in range, rounding may name the other
  /// one; where nothing returns, a surface beyond the range may go unnamed; gaps between arcs
  /// narrower than 1e-7 rad count as closed). Off only to measure its gain, and as the reference
  /// the culling is tested against.
  bool skip_occluded = true;
  /// How far past the sensor's range a surface is still predicted (named, returning nothing).
  /// 0 is exact for the pose predicted; a prediction whose surfaces other poses take up (an
  /// association cell's, cell_predictor_config()) needs how much nearer those poses can see them.
  double beyond_range_margin_m = 0.0;
};

/// False only when no forward ray of `ring` can meet the polygon whose outer-ring vertices (sensor
/// frame) are given. With g = (z − o)·cos φ − ρ·sin φ (ρ = √(x² + y²)), the ring's half-cone is
/// g = 0 (z ≥ o for φ > 0, z ≤ o for φ < 0); g is concave for φ ≥ 0 (its minimum over the polygon
/// is at a vertex) and convex for φ ≤ 0 (its maximum is), so "every vertex above the upward cone"
/// or "every vertex below the downward cone" holds for the whole polygon; so does "every vertex
/// below / above the apex plane" for an upward / downward cone. Conservative by a margin of
/// 1e-9 of the polygon's extent for rounding.
bool ring_cuts_polygon(const RingGeometry& ring, const double* x, const double* y, const double* z,
                       std::size_t count);

class ConicScanPredictor {
 public:
  /// Keeps a reference to `map`, which must outlive the predictor and not change (the polygon
  /// groups' boxes are computed here). Surfaces farther than
  /// `max_range_m` return nothing (a localizer hands down its one sensor range:
  /// localizer/models/range_sensor.hpp).
  ConicScanPredictor(const maps::PlaneMap& map, const sensor::LaserCalibration& calibration,
                     PredictorConfig config = {}, double max_range_m = sensor::kMaxRange_m);

  /// Predicts the scan of a sensor at T_map_sensor (map frame) from `candidate_polygons` (indices
  /// into map.polygons, e.g. a PlaneCuller result; any order, no duplicates needed). Fills
  /// out.rings (one per ring); allocates nothing once `out` has been used for a similar view.
  /// Thread-safe for distinct `out` objects.
  void predict(const Pose3& T_map_sensor, std::span<const int> candidate_polygons,
               PredictedScan& out) const;
  /// Same, over every polygon of the map.
  void predict(const Pose3& T_map_sensor, PredictedScan& out) const;
  /// Same as the first, for the rings listed in `rings` only (indices into rings(), ascending);
  /// the others are left empty (no surface). A prediction costs about a fixed part plus one
  /// part per ring: a scan that holds only some rings needs only those.
  void predict(const Pose3& T_map_sensor, std::span<const int> candidate_polygons,
               std::span<const int> rings, PredictedScan& out) const;

  const std::vector<RingGeometry>& rings() const { return rings_; }
  const PredictorConfig& config() const { return config_; }
  const maps::PlaneMap& map() const { return map_; }

 private:
  /// The groups (polygon_groups.hpp) holding `candidate_polygons` that some ring can reach
  /// within range, into workspace.groups, front to back by their nearest_m (with skip_occluded);
  /// `ring_count`: the rings predicted, for the counts of pairs left out.
  void select_groups(const Pose3& T_map_sensor, std::span<const int> candidate_polygons,
                     std::size_t ring_count, PredictedScan& out) const;
  /// Moves a group's polygons into the sensor frame with what the culling needs of them (their
  /// elevation bands, nearest_m, heights) and orders them front to back: once per prediction,
  /// when a ring first needs them.
  void prepare_group(PredictionWorkspace::Group& group, const Pose3& T_map_sensor,
                     PredictedScan& out) const;
  /// Ring k's arcs, group by group, and its envelope (out.rings[k]).
  void predict_ring(std::size_t k, const Pose3& T_map_sensor, PredictedScan& out) const;
  /// Clips the polygons of `group` for `ring`, nearest first; with skip_occluded, leaves the
  /// group out whole when it lies beyond the range or behind the ring's arcs so far (nearest_m:
  /// a lower bound on the range at which the ring's rays meet its box), and each polygon so.
  void visit_group(const RingGeometry& ring, PredictionWorkspace::Group& group, double nearest_m,
                   const Pose3& T_map_sensor, PredictedScan& out) const;
  /// A lower bound on the distance from any ring's apex, along its rays, to a point with height
  /// in [low, high] (sensor frame).
  double reach_any_ring(double low, double high) const;

  const maps::PlaneMap& map_;
  PolygonGroups groups_;
  std::vector<RingGeometry> rings_;
  PredictorConfig config_;
  double max_range_m_;
  double beyond_range_m_;  ///< max_range_m_ + config_.beyond_range_margin_m
  // What the rings fix: the largest apex offset and the lowest and highest elevations.
  double max_offset_m_ = 0.0;
  double lo_elevation_rad_ = 0.0, hi_elevation_rad_ = 0.0;
  double sin_lo_elevation_ = 0.0, sin_hi_elevation_ = 0.0;
  std::vector<int> all_polygons_;
  std::vector<int> all_rings_;
};

}  // namespace conicloc::localizer
