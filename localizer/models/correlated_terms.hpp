#pragma once
// How many independent measurements a scan is worth. Returns from one surface are not
// independent: the map error of that surface (a wall drawn 3 cm off), the calibration and the
// clutter standing in front of it are shared by all of them, so a wall seen by 800 beams does not
// pin the pose 800 times better than one beam does. Scoring a scan as thousands of independent
// terms makes its likelihood far sharper than what it knows: the cloud collapses onto one
// particle (spread 0), the estimate is that particle, and the filter cannot follow what the map
// leaves open, such as the position along a corridor.
//
// Model: each return's error is e_i = s + u_i, with s shared by every return of its surface
// (σ_s) and u_i its own (σ_u), σ² = σ_s² + σ_u². The n errors of a surface are then
// equicorrelated with ρ = σ_s²/σ², and their mean has the variance of
//   n_eff = n / (1 + (n − 1)ρ)
// independent terms (Kish's design effect, Survey Sampling 1965, 8.2): about 1/ρ for a large
// wall, nearly n for a door frame or pillar seen by a few beams. The scan's likelihood is
// tempered to the sum of n_eff over its surfaces (ParticleFilter::weight).
//
// A surface is a plane, not a polygon: the faces of one wall split by door openings or cell
// boundaries share its map error. Returns that no surface explains at the reference pose (within
// the model's inlier gate: clutter, openings into what the map lacks) say nothing of the pose
// there and count nothing. The reference pose is the particle that explains the scan best.

#include <span>
#include <vector>

#include "maps/plane_map.hpp"

namespace conicloc::localizer {

/// Σ n / (1 + (n − 1)ρ) over groups of `sizes` terms each (groups of ≤ 0 terms count 0).
inline double effective_term_count(std::span<const double> sizes, double correlation) {
  double count = 0.0;
  for (const double n : sizes) {
    if (n > 0.0) count += n / (1.0 + (n - 1.0) * correlation);
  }
  return count;
}

/// The surface of every polygon of a map: polygons on one oriented plane share an index.
struct Surfaces {
  std::vector<int> of_polygon;  ///< per polygon, in [0, count)
  std::size_t count = 0;
  /// Per surface: the horizontal part (x, y) of its plane's normal, map frame.
  std::vector<Eigen::Vector2d> horizontal_normal;
};

/// Polygons of `map` whose normals agree within `angle_rad` and offsets within `offset_m` are
/// one surface.
Surfaces coplanar_surfaces(const maps::PlaneMap& map, double angle_rad = 0.02,
                           double offset_m = 0.02);

/// Explained returns counted per surface, for effective_term_count().
class SurfaceTally {
 public:
  explicit SurfaceTally(const Surfaces& surfaces)
      : surfaces_(surfaces), returns_(surfaces.count, 0.0) {}
  /// `returns` more on the surface of map polygon `polygon`.
  void add(int polygon, double returns) {
    returns_[static_cast<std::size_t>(surfaces_.of_polygon[static_cast<std::size_t>(polygon)])] +=
        returns;
  }
  double effective_terms(double correlation) const {
    return effective_term_count(returns_, correlation);
  }
  /// Returns counted on surface `surface`.
  double returns_on(int surface) const { return returns_[static_cast<std::size_t>(surface)]; }
  const Surfaces& surfaces() const { return surfaces_; }

 private:
  const Surfaces& surfaces_;
  std::vector<double> returns_;
};

/// Exponents of a scan's terms (each ≥ 1, relative to the scan's tempering τ = n_eff / Σ size) that
/// give each sideways direction of the pose what the surfaces facing it are worth. Under one τ
/// for all terms a surface's share of the scan follows its returns: along a hall, whose floor,
/// ceiling and side walls hold most of them, the far end walls count a few per cent of a scan
/// that they alone inform. For a surface g facing sideways (|n_h| ≥ sin 30°, u = n_h/|n_h|), what
/// the equal exponents give direction u, E(u) = Σ_k τ·m_k·(n_hk·u)², is compared with what the
/// surfaces are worth there, W(u) = Σ_k m_k/(1 + (m_k − 1)ρ)·(n_hk·u)² (m_k the returns counted on
/// surface k, n_hk its horizontal normal), and g's terms are raised by W(u)/E(u) where that
/// exceeds 1. Never lowered: a direction that many returns fix keeps them, and among the surfaces
/// facing one direction the shares stay as they were (weighing each surface alike instead let a
/// house's small surfaces near the sensor, where maps are least right, turn the heading).
/// Terms on no surface (`surface_of_term` −1) and on floors and ceilings keep 1.
/// `scan_returns`: the returns all the scan's terms stand for, explained or not (τ's denominator).
std::vector<double> direction_term_weights(std::span<const int> surface_of_term,
                                           double scan_returns, const SurfaceTally& tally,
                                           double correlation);

}  // namespace conicloc::localizer
