#pragma once
// The shortcuts of the conic models' prediction. The tools always take them; the reference paths
// they replaced are kept to measure a shortcut's gain (bench_localizer) and to check it against
// (tests), so they are switched here, apart from the models' configs.

namespace conicloc::localizer {

struct PredictionShortcuts {
  /// conic-beam: beams associated with polygons per cell of a pose grid (association_grid.hpp);
  /// false: a full prediction per particle.
  bool association_grid = true;
  /// Both conic models: level cells that differ only in yaw share one prediction, turned in
  /// azimuth (yaw_shared_prediction.hpp; equal up to rounding).
  bool share_prediction_across_yaw = true;
  /// conic-beam scoring the mixture (ConicBeamConfig::max_mixture false; by default it scores the
  /// max form, which takes no log): the beams' log-likelihoods summed with one log per chunk of
  /// beams (BeamLikelihoodSum, the same likelihood); false: one log per beam
  /// (BeamMixture::log_likelihood).
  bool chunked_log = true;
};

}  // namespace conicloc::localizer
