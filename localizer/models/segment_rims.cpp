#include "localizer/models/segment_rims.hpp"

#include <cmath>
#include <numbers>
#include <optional>

namespace conicloc::localizer {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// A prediction may leave a piece of no width where two arcs meet (conic_beam_model.cpp): no piece.
constexpr double kZeroWidth = 1e-12;

// A piece of a ring's partition, unwrapped: its azimuths are boundary_rad + turn.
struct Cursor {
  std::size_t piece = 0;
  double turn = 0.0;
};

// Walks a ring's pieces around one segment, telling those of one surface from the rest.
class ArcWalk {
 public:
  ArcWalk(const PredictedRing& ring, const Surfaces& surfaces, int surface)
      : ring_(ring), surfaces_(surfaces), surface_(surface) {}

  // The piece holding an azimuth and its turn, wrapped once so that both agree (an azimuth a
  // rounding below a multiple of 2π would otherwise fall in one turn and the next's first piece).
  Cursor at(double azimuth_rad) const {
    double turn = std::floor(azimuth_rad / kTwoPi) * kTwoPi;
    double wrapped = azimuth_rad - turn;
    if (wrapped >= kTwoPi) wrapped -= kTwoPi, turn += kTwoPi;
    return {ring_.piece_at(wrapped), turn};
  }
  bool on(const Cursor& c) const {
    const int polygon = ring_.polygon[c.piece];
    return polygon >= 0 && surfaces_.of_polygon[static_cast<std::size_t>(polygon)] == surface_;
  }
  bool empty(const Cursor& c) const { return width(c) <= kZeroWidth; }
  // The piece's bound on the side of `direction` (+1: its end, −1: its beginning).
  double bound(const Cursor& c, int direction) const {
    return ring_.boundary_rad[c.piece + (direction > 0 ? 1 : 0)] + c.turn;
  }
  Cursor step(Cursor c, int direction) const {
    const std::size_t n = ring_.piece_count();
    if (direction > 0) {
      if (++c.piece == n) c.piece = 0, c.turn += kTwoPi;
    } else if (c.piece == 0) {
      c.piece = n - 1, c.turn -= kTwoPi;
    } else {
      --c.piece;
    }
    return c;
  }
  BoundarySide side(const Cursor& c) const {
    return {ring_.polygon[c.piece], ring_.a[c.piece], ring_.b[c.piece], ring_.c[c.piece]};
  }

 private:
  double width(const Cursor& c) const {
    return ring_.boundary_rad[c.piece + 1] - ring_.boundary_rad[c.piece];
  }
  const PredictedRing& ring_;
  const Surfaces& surfaces_;
  int surface_;
};

// The end, on the side of `direction`, of the arc of the walk's surface that holds the segment's
// returns up to `outermost_rad` (its last return on that side; `innermost_rad` the other): the
// last piece of the surface (`inside`) and the first other piece of some width past it
// (`outside`). nullopt when the surface covers no part of the segment near that side, or its arc
// ends more than kMaxReach_rad from the segment's outermost return.
struct ArcEnd {
  Cursor inside, outside;
  double azimuth_rad;
};
std::optional<ArcEnd> arc_end(const ArcWalk& walk, std::size_t pieces, double outermost_rad,
                              double innermost_rad, int direction) {
  Cursor c = walk.at(outermost_rad);
  Cursor inside = c;
  std::size_t steps = 0;
  if (walk.on(c) && !walk.empty(c)) {
    // The segment ends on the surface: its arc goes on to the first other piece.
    for (;; ++steps) {
      if (steps == pieces) return std::nullopt;  // the whole ring is one surface
      const Cursor next = walk.step(c, direction);
      c = next;
      if (walk.empty(next)) continue;
      if (!walk.on(next)) break;
      inside = next;
      if (direction * (walk.bound(next, -direction) - outermost_rad) > SegmentRims::kMaxReach_rad)
        return std::nullopt;
    }
  } else {
    // The segment runs past the surface's arc at the centre: the arc's last piece inside it.
    for (;; ++steps) {
      if (steps == pieces || direction * (walk.bound(c, -direction) - innermost_rad) <= 0.0)
        return std::nullopt;
      c = walk.step(c, -direction);
      if (!walk.empty(c) && walk.on(c)) break;
    }
    inside = c;
    do c = walk.step(c, direction);
    while (walk.empty(c));
  }
  const double azimuth = walk.bound(inside, direction);
  if (std::abs(azimuth - outermost_rad) > SegmentRims::kMaxReach_rad) return std::nullopt;
  return ArcEnd{inside, c, azimuth};
}

}  // namespace

void SegmentRims::clear() {
  rates.clear();
  limit_rad.clear();
  outermost_rad.clear();
  returns_per_rad.clear();
  term.clear();
}

void find_segment_rims(const Association& association, const std::vector<SegmentFit>& fits,
                       const PredictedScan& predicted, const maps::PlaneMap& map,
                       const std::vector<RingGeometry>& rings, const Surfaces& surfaces,
                       const Pose3& centre, const AssociationCellSize& cell, SegmentRims& out) {
  out.clear();
  const double half_diagonal_m = cell.half_diagonal_m(), half_angle_rad = 0.5 * cell.angle_rad;
  // A pose of the cell is within the half diagonal of the centre and turned by at most 3/2 of the
  // cell's angle (roll, pitch and yaw composed; segment_landmarks.hpp).
  const double max_rotation_rad = 1.5 * cell.angle_rad;
  for (std::size_t t = 0; t < association.terms.size(); ++t) {
    const AssociatedTerm& associated = association.terms[t];
    const SegmentFit& fit = fits[static_cast<std::size_t>(associated.fit)];
    const PredictedRing& ring = predicted.ring(fit.ring);
    const std::size_t pieces = ring.piece_count();
    const double span = fit.end_rad - fit.begin_rad;
    if (pieces == 0 || !(fit.returns > 1.0) || !(span > 0.0)) continue;
    const int polygon =
        association.landmarks[static_cast<std::size_t>(associated.landmark)].polygon;
    const ArcWalk walk(ring, surfaces, surfaces.of_polygon[static_cast<std::size_t>(polygon)]);
    for (const int direction : {-1, +1}) {
      const double outermost = direction > 0 ? fit.end_rad : fit.begin_rad;
      const double innermost = direction > 0 ? fit.begin_rad : fit.end_rad;
      const auto end = arc_end(walk, pieces, outermost, innermost, direction);
      if (!end) continue;
      // boundary_motion takes the sides in azimuth order.
      const Cursor& before = direction > 0 ? end->inside : end->outside;
      const Cursor& after = direction > 0 ? end->outside : end->inside;
      const auto motion = boundary_motion(map, rings[static_cast<std::size_t>(fit.ring)], centre,
                                          end->azimuth_rad, walk.side(before), walk.side(after));
      if (!motion) continue;
      const double returns_per_rad = (fit.returns - 1.0) / span;
      const double max_shift = motion->per_translation.norm() * half_diagonal_m +
                               motion->per_rotation.lpNorm<1>() * half_angle_rad;
      if (max_shift * max_shift * returns_per_rad > SegmentRims::kMaxCornerError_returns) continue;
      // An end that no pose of the cell moves inside the segment's outermost half spacing counts
      // nothing anywhere in it: left out.
      const double reach = motion->per_translation.norm() * half_diagonal_m +
                           motion->per_rotation.norm() * max_rotation_rad;
      if (direction * (outermost - end->azimuth_rad) + reach <= -0.5 / returns_per_rad) continue;
      // Stored signed by the direction, so that returns beyond are (outermost − limit) > 0.
      out.rates.add(*motion, direction);
      out.limit_rad.push_back(direction * end->azimuth_rad);
      out.outermost_rad.push_back(direction * outermost);
      out.returns_per_rad.push_back(returns_per_rad);
      out.term.push_back(static_cast<int>(t));
    }
  }
}

void returns_beyond_rims(const SegmentRims& rims, const PoseOffset& offset, std::size_t terms,
                         std::vector<double>& shifts, Eigen::ArrayXd& beyond) {
  beyond.setZero(static_cast<Eigen::Index>(terms));
  const std::size_t count = rims.size();
  if (count == 0) return;
  rims.rates.shifts(offset, shifts);
  const double* shift = shifts.data();
  for (std::size_t k = 0; k < count; ++k) {
    if (!(std::abs(shift[k]) <= SegmentRims::kMaxShift_rad)) continue;
    const double past = rims.outermost_rad[k] - (rims.limit_rad[k] + shift[k]);
    const double returns = past * rims.returns_per_rad[k] + 0.5;
    if (returns > 0.0) beyond(rims.term[k]) += returns;
  }
}

}  // namespace conicloc::localizer
