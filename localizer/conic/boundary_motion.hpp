#pragma once
// How a boundary of a predicted scan line moves when the pose moves within its association cell.
//
// A ring's scan line changes surface where its cone crosses an edge: the rim of the nearer
// polygon (a door jamb, the end of a ceiling, the outline of a pillar), or the line where two
// planes meet (a wall on the floor). A model that predicts the scan once per cell of pose space
// (association_grid.hpp) and moves only the planes to each particle keeps the boundaries where
// the cell's centre saw them, up to half a cell (12 cm, 1°) away. Within the cell the likelihood
// then ignores every edge, and it jumps where the next cell begins. Along a corridor, where the
// edges (door openings, corners) are what fixes the position, a scan scored this way has a
// staircase for a profile: flat for 25 cm, then a step of a hundred nats or more. That made issue
// 14's late 10–15 cm errors without odometry. Carrying, per boundary, the rate at which its
// azimuth moves with the pose lets each particle move it to where its own ring crosses the edge.
//
// The edge is a 3D line through X₀, the point where the centre's ring met it, along u. In the
// sensor frame of a pose T = T_c·exp(ξ), ξ = (δt, δω) small (centre's sensor frame), the line is
// P(s) ≈ P₀ − δt − δω × P₀ + s·U (P₀ = X₀ and U = u in the centre's sensor frame). The ring's
// cone is f(p) = (p_z − o)·cos φ − |p_xy|·sin φ = 0, whose gradient is g = (−sin φ·p_x/ρ,
// −sin φ·p_y/ρ, cos φ) at P₀, ρ = |P₀_xy|. The crossing moves by ds = −g·dP / g·U, and its azimuth
// θ = atan2(p_y, p_x) by h·dp with h = (−p_y, p_x, 0)/ρ². So
//   δθ = w·dP,  w = h − g·(h·U)/(g·U),  dP = −δt + P₀ × δω,
//   δθ = −w·δt + (w × P₀)·δω.
// The rate is exact to first order; the second-order error is about (shift / range)², 0.07° for
// 18 cm at 5 m, and larger where the ring meets the edge near tangency.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "localizer/conic/pose.hpp"
#include "localizer/conic/ring_geometry.hpp"
#include "maps/plane_map.hpp"

namespace conicloc::localizer {

/// One side of a boundary as the predicting pose saw it: the map polygon (−1: nothing) and its
/// conic's inverse range 1/r = a cos θ + b sin θ + c.
struct BoundarySide {
  int polygon = -1;
  double a = 0.0, b = 0.0, c = 0.0;
};

/// A pose's offset from the predicting pose T_c, in T_c's sensor frame: T = T_c·exp(ξ).
struct PoseOffset {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();  ///< δt
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();  ///< δω, the small-angle vector of R_cᵀR
};
PoseOffset pose_offset(const Pose3& T_centre, const Pose3& T);

/// Where a boundary lies at the predicting pose and how fast it moves with the pose.
struct BoundaryMotion {
  double azimuth_rad = 0.0;
  Eigen::Vector3d per_translation = Eigen::Vector3d::Zero();  ///< ∂θ/∂δt, rad/m
  Eigen::Vector3d per_rotation = Eigen::Vector3d::Zero();     ///< ∂θ/∂δω
  /// The boundary's azimuth at a pose `offset` from the predicting one.
  double azimuth_at(const PoseOffset& offset) const {
    return azimuth_rad + per_translation.dot(offset.translation) +
           per_rotation.dot(offset.rotation);
  }
};

/// The rates of many boundaries, by column (∂θ/∂δt x, y, z, then ∂θ/∂δω x, y, z), so that the
/// shifts of them all at one pose are six passes of multiply-adds over contiguous arrays.
class BoundaryRates {
 public:
  std::size_t size() const { return columns_[0].size(); }
  void clear();
  /// Appends `motion`'s rates times `sign` (−1 for a boundary whose azimuth is kept negated).
  void add(const BoundaryMotion& motion, double sign = 1.0);
  /// Each boundary's δθ = rate·(δt, δω) at a pose `offset` from the predicting one.
  void shifts(const PoseOffset& offset, std::vector<double>& out) const;

 private:
  std::array<std::vector<double>, 6> columns_;
};

/// The motion of the boundary at azimuth `azimuth_rad` of `ring`, predicted at T_map_sensor
/// between `before` (smaller azimuths) and `after`. Its edge:
/// - both sides' planes meet the beam at the same range (within 10⁻³ of it): the planes'
///   intersection line (a wall on the floor, or two walls crossing);
/// - otherwise the nearer side's polygon ends there: the edge of its outline or of a hole nearest
///   the hit, when one passes within `edge_tolerance_m` (+ 10⁻³ of the range).
/// nullopt where no edge explains the boundary (one plane split in two, a boundary set by the
/// sensor's range limits) or the ring runs along the edge: such a boundary stays where it was.
std::optional<BoundaryMotion> boundary_motion(const maps::PlaneMap& map, const RingGeometry& ring,
                                              const Pose3& T_map_sensor, double azimuth_rad,
                                              const BoundarySide& before, const BoundarySide& after,
                                              double edge_tolerance_m = 0.02);

}  // namespace conicloc::localizer
