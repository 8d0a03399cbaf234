#pragma once
// Calibration by least squares of measured returns against the map's planes (paper: scans of
// known planes measure the lasers). State: per laser (Δφ, Δo, Δψ, Δd), the mounting (h, roll,
// pitch) and per scan (x, y, yaw and the carrier's velocity v_x, v_y, ω and yaw acceleration α
// through the scan: the de-skew, calibration_model.hpp), refined jointly by Levenberg–Marquardt on
// Huber-weighted residuals q(c)·(r − r̂): the range error along the ray over its standard deviation
// at the incidence cosine c, held through each step (calib/return_noise.hpp: range noise and
// surface error, fitted to the residuals; calib/calibration_model.hpp: derivatives free of the
// range noise), with
// the returns re-associated before each round under a shrinking gate (calib/plane_association.hpp:
// the first polygon near the point that the ray meets, inside its edges and clear of the others').
//
// Gauge: a common vertical offset of every laser is a change of height (and of the scans' x, y),
// a common azimuth offset a change of every scan's yaw (and of roll/pitch axes), so the state
// is pinned by mean Δo = 0 and mean Δψ = 0 over the lasers where each is observable (stiff
// pseudo-residuals). Corrections a laser cannot observe (calib/laser_observability.hpp), judged
// at the start of every round (the last round's verdict is reported), are held at 0.
// Sigmas: the diagonal of the M-estimator's sandwich H⁻¹·M·H⁻¹ at the solution, H = Σ ψ'(e)·JJᵀ
// (Huber's curvature: 1 within k, 0 beyond; with the priors) and M = Σ_lines s·sᵀ + σ²·P,
// s = Σ_line ψ(e)·J the gradient of one scan line (a laser in a scan), P the priors' precisions:
// what the model leaves out along a line (a de-skew's left-over, an edge, an object the map
// lacks) is shared by its returns, and the weights are fitted, not known. The model's sigma is
// beside it, (Σψ²/(N − free parameters))/ρ·H⁻¹ with ρ the share of returns within k (σ²·H⁻¹
// when all are): it is the sandwich's only where the returns are independent with the variance
// the weights assume (FJK-Haus, weighed by the cosine alone: the up-looking lasers' elevations
// 3–5 times too narrow). Each sigma is the larger of the two: with few scan lines the sandwich
// can come out below what white noise alone leaves. In a Monte Carlo of one capture (the
// example building, 12 s, the noise redrawn with `simulate --noise-seed`) the lasers' corrections
// spread as these sigmas say; the floor's mode (height, tilt, down-looking lasers) perhaps 1.2–1.6
// times wider. The gradient matches finite differences of the cost, and H (Huber off) those of
// the gradient, at a solution (docs/results/calibration-weights.md).
//
// Plane adjustment: the map is a survey, its walls centimetres off and out of plumb. Held fixed,
// those errors go into the lasers: a wall 2 cm off seen at 4 m moves an elevation by 0.3°
// (a tilted VLP-16 in the example building with 2 cm map error: elevations 0.35° RMS off, 0.047°
// with an exact map). So every polygon the returns fall on gets a correction (offset and two
// tilts, calibration_model.hpp) with the prior N(0, σ_map²) on the offset and σ_map/extent on each
// tilt (MAP, weighed against the returns' residual variance): the lasers share what all planes
// see, a plane's own error stays with the plane. Moving the whole map with the scans' poses, or
// the floors and ceilings with the height, fits the returns alike: those common shifts are held
// by the prior alone, so a plane's offset and sigma include them (and the height's sigma grows).
// Only polygons met in the first round (at the widest gate) are adjusted.

#include <array>
#include <cmath>
#include <vector>

#include "calib/calibration_model.hpp"
#include "calib/laser_observability.hpp"
#include "calib/return_noise.hpp"
#include "calib/unmapped_objects.hpp"
#include "maps/plane_map.hpp"
#include "sensor/laser_calibration.hpp"

namespace conicloc::calib {

struct CalibrationConfig {
  std::vector<double> gates_m = {0.30, 0.15, 0.10};  ///< association gate per round
  int max_iterations = 15;                           ///< Levenberg–Marquardt steps per round
  double huber_m = 0.05;                             ///< residuals beyond this weigh k/|e|
  /// A return counts only where its ray meets the polygon this far inside its edges and passes
  /// the others' this far (plane_association.hpp: by an edge, which surface a return came from
  /// turns on the millimetres between the modelled ray and the true one).
  double edge_margin_m = 0.10;
  double step_tolerance = 1e-12;                     ///< stop when max |Δx| is below this
  double cost_tolerance = 1e-12;                     ///< or the cost falls by less (relative)
  std::size_t max_extra_rounds = 10;  ///< at the last gate, while the associations change
  /// The search box of the corrections (|Δφ|, |Δo|, |Δψ|, |Δd|): a sensor is calibrated to well
  /// within these at the factory. Without them a laser whose returns are mostly floor can
  /// "collapse" onto it (φ → 0, o → −h fits every floor return exactly, a degenerate cone).
  std::array<double, 4> max_correction = {1.0 * M_PI / 180.0, 0.03, 1.0 * M_PI / 180.0, 0.10};
  /// How far the map's planes may stand from where it puts them (std. dev. of the offset; the
  /// tilts' is this over the surface's extent). 0 holds the planes fixed.
  double map_sigma_m = 0.02;
  /// ... except floors and ceilings, which are built level: their tilts' std. dev. (rad).
  double level_tilt_sigma = 1e-3;
  ObservabilityConfig observability;
  /// From the second round on, the returns of objects the map lacks by a surface are left out
  /// (unmapped_objects.hpp); median_sigmas ≤ 0 keeps them.
  UnmappedObjectConfig unmapped_objects;
  /// From the second round on, each return weighs by its residual's variance σ_r² + σ_s²/c²,
  /// both fitted to the residuals (return_noise.hpp); min_returns above the returns' count keeps
  /// the first round's weights (c²: surface error alone).
  ReturnNoiseConfig return_noise;
  /// Threads over the returns (0: all cores). The sums run over fixed blocks of returns added
  /// in block order, so the result is the same for any number.
  int threads = 1;
};

struct LaserEstimate {
  LaserCorrection correction;
  std::array<double, 4> sigma{};  ///< of Δφ (rad), Δo (m), Δψ (rad), Δd (m) (Sigmas above)
  std::array<double, 4> model_sigma{};  ///< the same from σ²·H⁻¹ (independent returns)
  LaserObservability observability;
  int returns = 0;  ///< associated in the last round
  int planes = 0;   ///< planes with enough returns
};

/// One map polygon's adjustment.
struct PlaneEstimate {
  int polygon = -1;  ///< index into the map's polygons
  PlaneCorrection correction;
  std::array<double, 3> sigma{};  ///< of δ (m), s_u, s_v
  int returns = 0;                ///< associated in the last round
};

/// The sensor's height above the floor as the fit places that floor: h plus the carrier's
/// distance above the floor polygon under it, adjusted (δ + s_u·u + s_v·v) or held, averaged over
/// the scans (the model's h is above the map's floor). The floors and the sensor moving up or
/// down together fit the returns alike, held by the floors' priors alone (above), so h follows
/// the floors' common error (FJK-Haus, 36 s: 4.6 and 6.3 cm low with the floor under it 4.2 and
/// 6.1 cm low); the floor's returns measure the height above it directly (3.8 and 2.5 mm off).
struct FloorHeight {
  double height_m = 0.0;
  double sigma_m = 0.0;  ///< from the covariance of h and the floors' corrections
  int scans = 0;         ///< over a floor polygon of the map (0: none found; h and its sigma)
};

struct CalibrationResult {
  std::vector<LaserEstimate> lasers;  ///< channel order
  Mounting mounting;
  std::array<double, 3> mounting_sigma{};  ///< h (m), roll, pitch (rad) (Sigmas above)
  FloorHeight height_above_floor;
  std::vector<ScanPose> poses;         ///< with the velocities fitted
  std::vector<PlaneEstimate> planes;  ///< the adjusted polygons (none when map_sigma_m is 0)
  std::size_t returns = 0;            ///< associated in the last round
  std::size_t unmapped_returns = 0;   ///< left out in the last round (unmapped_objects.hpp)
  double rms_m = 0.0;                 ///< of the associated residuals, unweighted
  double sigma_m = 0.0;               ///< the weighted residual σ behind the sigmas
  ReturnNoise noise;                  ///< the last round's (return_noise.hpp)
  int iterations = 0;
  bool converged = false;  ///< the last round's step or cost change fell below tolerance
};

/// Fits the corrections to `decode` (the calibration the returns were decoded with), starting
/// from `mounting` and `poses`. Throws std::invalid_argument when a return names a laser or scan
/// that does not exist, or no return lies on a map plane.
CalibrationResult calibrate(const maps::PlaneMap& map, const sensor::LaserCalibration& decode,
                            const std::vector<Return>& returns, const Mounting& mounting,
                            const std::vector<ScanPose>& poses, const CalibrationConfig& config);

}  // namespace conicloc::calib
