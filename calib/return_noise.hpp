#pragma once
// How far a return's range strays from where its ray meets its surface, and so how much each
// return weighs in the fit (calibration_solver.hpp).
//
// Two sources, with one variance each:
// - the range noise of the sensor, σ_r along the ray, whatever the incidence;
// - the surface standing off its plane (a survey's left-over error after the plane's own
//   adjustment, a wall not quite flat, a return by an edge on the neighbouring surface), σ_s
//   across the surface. Met at the incidence cosine c = |a·d| it is σ_s/c along the ray.
// So the range residual r − r̂ of a return has the variance
//   V(c) = σ_r² + σ_s²/c²,
// and the fit weighs (r − r̂)/√V(c). Weighing c·(r − r̂) alone, as if only σ_s were there,
// underweighs a return met at a slant by V/(c²·V(1)) where the range noise rules: a ceiling seen
// at 60° counts for a quarter of what it holds (FJK-Haus: up-looking lasers' elevations 0.10–0.17°
// off at 3 cm of range noise, at 4 of their reported σ; a per-return sandwich covariance,
// H⁻¹·Σw²e²JJᵀ·H⁻¹, measured in session 42's scratch build, gave them 3–5 times those σ).
//
// The solver keeps its residuals in metres at normal incidence: it fits
//   e = q(c)·(r − r̂),   q(c) = √(V(1)/V(c)) = c·√((σ_r² + σ_s²)/(c²σ_r² + σ_s²)),
// which is c·(r − r̂) when σ_r = 0 and r − r̂ when σ_s = 0, so the Huber threshold, the residual
// variance behind the priors and the unmapped-object test mean what they did.
//
// The two variances are read off the residuals: sorted by u = 1/c² into bins of equal count,
// each bin's robust variance (1.4826·MAD)² against its mean u is a line, σ_r² + σ_s²·u,
// fitted by weighted least squares (a variance estimated from n samples has the spread
// √(2/n)·V, so each bin weighs n/V²) with both terms held ≥ 0. The median keeps objects the map
// lacks and wrong associations, up to half a bin, out of it.

#include <span>

namespace conicloc::calib {

struct ReturnNoise {
  double range_sigma_m = 0.0;    ///< σ_r, along the ray
  double surface_sigma_m = 0.0;  ///< σ_s, across the surface

  /// q(c) above: the factor on the range residual of a return met at incidence cosine c.
  /// With neither noise known (both 0) it is c, the point-to-plane residual's size; 0 for c ≤ 0.
  double residual_scale(double cosine) const;
};

/// The noise is not fitted (ReturnNoise{}: weights c) with fewer than 2 bins, or fewer returns
/// than min_returns or than 2 per bin.
struct ReturnNoiseConfig {
  int bins = 10;          ///< of equal count over 1/c²
  int min_returns = 200;
};

/// σ_r and σ_s from the range residuals r − r̂ of the associated returns and their incidence
/// cosines. Throws std::invalid_argument when the lengths differ, a cosine is not finite and > 0
/// (an adjusted plane's |a·d| may be a hair over 1) or a residual is not finite. Residuals of two
/// clusters (±3 cm twins) have a MAD that depends on where each bin's median falls: the fit assumes
/// one peak.
ReturnNoise fit_return_noise(std::span<const double> range_residuals_m,
                             std::span<const double> cosines, const ReturnNoiseConfig& config = {});

}  // namespace conicloc::calib
