#pragma once
// The scan a pose predicts: per ring, a piecewise-conic scan line over the azimuth circle
// (DESIGN.md "Bounded planes"). Each piece is one polygon's conic in the linear form
//   1/r = a cos θ + b sin θ + c      (so r = 1 / (a cos θ + b sin θ + c)),
// and the pieces partition [0, 2π) in azimuth order. Gaps (no surface) are pieces with
// a = b = c = 0 and polygon −1. Evaluating at sorted measured azimuths is one merge walk.

#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "localizer/conic/occlusion_bins.hpp"
#include "localizer/conic/polygon_groups.hpp"

namespace conicloc::localizer {

/// Cos and sin of a sorted list of measured azimuths (radians in [0, 2π)), computed once per scan
/// and shared by every pose: the azimuths are sensor-frame, so they do not depend on the pose.
struct AzimuthSamples {
  std::vector<double> azimuth_rad;
  std::vector<double> cos_azimuth;
  std::vector<double> sin_azimuth;

  /// Precondition: `sorted_azimuths_rad` ascending, within [0, 2π).
  void assign(std::span<const double> sorted_azimuths_rad);
  std::size_t size() const { return azimuth_rad.size(); }
};

/// One ring's predicted scan line. Structure of arrays: piece i covers
/// [boundary_rad[i], boundary_rad[i+1]); boundary_rad.front() = 0, boundary_rad.back() = 2π.
struct PredictedRing {
  /// Returned where the pose predicts no return: nothing hit, or the nearest surface along the
  /// beam is closer than min_range_m or farther than max_range_m (the sensor reports nothing).
  static constexpr double kNoReturn = std::numeric_limits<double>::infinity();

  std::vector<double> boundary_rad;  ///< piece_count() + 1 ascending azimuths
  std::vector<double> a, b, c;       ///< 1/r coefficients per piece (0, 0, 0 for a gap)
  std::vector<int> polygon;          ///< index into PlaneMap::polygons per piece, −1 for a gap
  double min_inverse_range = 1.0 / 100.0;  ///< 1 / the sensor's maximum range
  double max_inverse_range = 1.0 / 0.3;    ///< 1 / min_range_m

  std::size_t piece_count() const { return a.size(); }
  /// Index of the piece covering θ (wrapped into [0, 2π)).
  std::size_t piece_at(double azimuth_rad) const;
  /// Predicted range at one azimuth (any value, wrapped), or kNoReturn.
  double range(double azimuth_rad) const;
  /// Predicted range per azimuth: one merge walk over the pieces. Precondition: azimuths sorted
  /// ascending in [0, 2π) and ranges_out.size() == azimuths.size(). Computes cos/sin per beam;
  /// the AzimuthSamples overload avoids that (the per-particle hot path).
  void evaluate_sorted(std::span<const double> azimuths_rad, std::span<double> ranges_out) const;
  void evaluate_sorted(const AzimuthSamples& samples, std::span<double> ranges_out) const;

  /// Empties the ring (keeps capacity) and starts a new partition at θ = 0.
  void clear();
  /// Appends the piece from the last boundary to `end_rad`, or extends the last piece when it is
  /// the same surface with the same coefficients.
  void append(double end_rad, double a_piece, double b_piece, double c_piece, int polygon_piece);
};

/// Reusable working memory of ConicScanPredictor::predict(); owned by the caller through
/// PredictedScan (one per thread), so a prediction allocates nothing once warmed up.
struct PredictionWorkspace {
  struct Arc {
    double begin_rad, end_rad;  ///< within [0, 2π], begin < end
    double a, b, c;             ///< 1/r coefficients of the polygon's conic
    int polygon;
  };
  struct SensorPolygon {
    int polygon = -1;
    double normal[3] = {0, 0, 0};  ///< n_s
    double offset = 0.0;           ///< D_s
    double origin[3] = {0, 0, 0};  ///< plane frame origin, sensor frame
    double e_u[3] = {0, 0, 0}, e_v[3] = {0, 0, 0};
    /// Its vertex rings: ring_begin[i] .. ring_begin[i + 1] for i in [ring_entry_begin,
    /// ring_entry_end).
    std::size_t ring_entry_begin = 0, ring_entry_end = 0;
    double centre[3] = {0, 0, 0};  ///< bounding-sphere centre, sensor frame
    double radius = 0.0;
  };
  std::vector<SensorPolygon> polygons;
  std::vector<double> vertex_x, vertex_y, vertex_z;  ///< sensor frame, ring after ring
  std::vector<std::size_t> ring_begin;               ///< start of each vertex ring (+ end marker)
  std::vector<Arc> arcs;                             ///< of the ring being built
  std::vector<double> splits;  ///< switch points of the ring envelope's current interval
  /// Where a ring's beam crosses an edge of the polygon being clipped: azimuth and which of the
  /// polygon's vertex rings (0 = outer, 1.. = holes) the edge belongs to.
  struct EdgeCrossing {
    double azimuth_rad;
    int ring;
  };
  std::vector<EdgeCrossing> edge_crossings;
  std::vector<char> inside_ring;  ///< per vertex ring of the polygon being clipped
  std::vector<double> first_crossing, last_crossing;  ///< per vertex ring: its crossings' span
  std::vector<double> events;
  std::vector<int> active;
  std::vector<int> contenders;  ///< active arcs that can be nearest in the current interval
  std::vector<double> bounds;
  std::vector<double> bands;  ///< elevation band [lo, hi] per polygon (radians)
  // Front-to-back occlusion culling (occlusion_bins.hpp), per group of polygons
  // (polygon_groups.hpp): the candidates by group, the groups in clipping order with their box
  // as the sensor sees it; per polygon: the clipping order (group by group), a bound on the
  // distance of its nearest point from any apex, |n_xy|, the height range of its outer
  // vertices (sensor frame), and its azimuth span (computed when first needed).
  struct Group {
    std::size_t members_begin = 0, members_end = 0;  ///< in group_members
    SensorBox view;
    double nearest_m = 0.0;  ///< lower bound on the distance from any apex along any ring's rays
    bool prepared = false;   ///< its polygons are in `polygons`, ordered in front_to_back
    std::size_t order_begin = 0, order_end = 0;  ///< in front_to_back
  };
  std::vector<std::size_t> group_start, group_fill;
  std::vector<int> group_members;  ///< candidate polygon indices (map), group by group
  std::vector<Group> groups;
  /// Groups a ring reaches only beyond their nearest_m (another storey's rooms, past a floor or
  /// ceiling): (their bound along the ring's rays, index in `groups`), visited last.
  std::vector<std::pair<double, std::size_t>> deferred;
  OcclusionBins occlusion;
  std::vector<int> front_to_back;
  std::vector<double> nearest_m, normal_xy, z_low, z_high;
  std::vector<AzimuthSpan> spans;
  std::vector<char> span_known;
};

/// The predicted scan of one pose: one PredictedRing per laser ring (indexed by ring, lowest
/// elevation first), plus the workspace reused by the next prediction (the predictor's alone).
struct PredictedScan {
  std::vector<PredictedRing> rings;
  std::size_t polygons_considered = 0;  ///< candidates given to predict()
  /// Candidates outside every ring's elevation (no ring tested): a group's all when its box is,
  /// else those of the groups moved into the sensor frame (polygons_prepared) whose own are.
  std::size_t polygons_outside_field_of_view = 0;
  /// (ring, polygon) pairs left out because nearer arcs of the ring hid the polygon.
  std::size_t ring_polygons_occluded = 0;
  /// (ring, polygon) pairs left out because the ring's rays meet the polygon (or its group's box)
  /// only beyond the sensor's maximum range (plus PredictorConfig::beyond_range_margin_m), where
  /// a return reads as none (a group's members once per ring when its box lies that far for
  /// every ring).
  std::size_t ring_polygons_beyond_range = 0;
  /// (ring, polygon) pairs clipped to arcs: the prediction's costly part.
  std::size_t ring_polygons_clipped = 0;
  /// Candidates moved into the sensor frame: those of the groups (polygon_groups.hpp) that some
  /// ring could not leave out whole.
  std::size_t polygons_prepared = 0;

  const PredictedRing& ring(int k) const { return rings[static_cast<std::size_t>(k)]; }

 private:
  friend class ConicScanPredictor;
  PredictionWorkspace workspace_;
};

}  // namespace conicloc::localizer
