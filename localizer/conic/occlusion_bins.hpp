#pragma once
// Front-to-back occlusion culling of one ring (DESIGN.md "Leave out what a scene does not need").
// A ring's prediction keeps, at every azimuth, the nearest surface (ring_envelope.hpp). When the
// polygons are clipped nearest first, the arcs already clipped bound how far the envelope can
// reach: the envelope E(θ) = min over arcs at θ of r_arc(θ), r_arc = 1 / (a cos θ + b sin θ + c),
// is at most r_A(θ) for any one arc A at θ. Each bin of the azimuth circle keeps a partition of
// the parts the arcs cover into segments, each owned by one arc and bounded by that arc's
// farthest range over it; the bin is covered out to
//   cover_b = max over its segments of  max_{θ ∈ segment} r_owner(θ)
// once they join over the whole bin. Where a new arc overlaps a segment, it takes the overlap
// over, whole, when its farthest range there is nearer than the owner's, and the owner's farthest
// range is recomputed over what it keeps: a floor seen down a corridor and the side wall beside it
// (that runs on beneath the floor, merged with the storey below) cover the bin out to the floor's
// range, not to the wall's farthest. A polygon whose nearest point lies beyond cover_b in every
// bin of its azimuth span is behind those arcs wherever a beam of the ring could meet it, so the
// envelope never picks it: skipping it leaves the prediction as it was. In a building the nearest
// walls, floor and ceiling close most of the view, and rooms and storeys behind them cost
// nothing.

#include <array>
#include <cstddef>

namespace conicloc::localizer {

/// Rounding allowance of azimuth spans (widened by it) and of arcs that meet (gaps up to it count
/// as closed): more than the clipping's own rounding of edge crossings (~1e-9 rad, more for
/// edges far from the sensor).
inline constexpr double kAzimuthSlack_rad = 1e-7;

/// The azimuths (sensor frame, counter-clockwise from x) at which a polygon's projection onto the
/// sensor's xy plane lies: [begin, begin + width) with begin in [0, 2π), or the whole circle.
struct AzimuthSpan {
  bool whole = true;
  double begin_rad = 0.0;
  double width_rad = 0.0;
};

/// The span of the polygon whose outer-ring vertices (sensor frame) are given. The whole circle
/// when the projection holds or touches the z axis (a ceiling above the sensor) or when an edge
/// passes within reach of it: unwrapping the vertex azimuths edge by edge is only sure there.
AzimuthSpan polygon_azimuth_span(const double* x, const double* y, std::size_t count);

class OcclusionBins {
 public:
  /// 5.6° bins: with 256 the covering costs more than the finer bins hide (bench_conic,
  /// BM_PredictInScaledBuilding: 256 bins 1.10–1.24× the time without culling in open corridor
  /// views, 64 bins 1.02–1.10×).
  static constexpr int kBins = 64;

  OcclusionBins();

  /// Nothing covered.
  void reset();
  /// Adds an arc over [begin_rad, end_rad] ⊂ [0, 2π] with 1/r = a cos θ + b sin θ + c > 0 on it.
  void cover(double begin_rad, double end_rad, double a, double b, double c);
  /// True when every bin of `span` is covered nearer than `nearest_m`.
  bool hides(const AzimuthSpan& span, double nearest_m) const;

 private:
  /// A part of a bin and a bound on the envelope over it: the farthest range of its owner arc
  /// (1/r = a cos θ + b sin θ + c) there. Its ends' cosines and sines are kept to recompute that
  /// range over a smaller part without trigonometry.
  struct Segment {
    double begin_rad, end_rad;
    double cos_begin, sin_begin, cos_end, sin_end;
    double a, b, c, R;  ///< R = |(a, b)|
    double farthest_m;
  };
  /// Segments per bin. More (door jambs down a corridor): neighbours that meet are joined into one
  /// bounded by the larger range (a constant: a = b = 0, c = 1/r), else the narrowest is dropped
  /// (less covered, never wrongly more).
  static constexpr int kSegments = 6;
  struct Bin {
    std::array<Segment, kSegments> segments;
    int count = 0;
  };
  /// Adds an arc's part inside `bin` (a Segment with its farthest range over the part).
  void cover_bin(int bin, const Segment& part);

  std::array<double, kBins> cover_m_;
  std::array<Bin, kBins> bins_;
  std::array<double, kBins + 1> cos_edge_, sin_edge_;  ///< at θ_b = 2π b / kBins
};

}  // namespace conicloc::localizer
