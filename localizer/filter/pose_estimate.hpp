#pragma once
// The pose estimate of a weighted particle set: the weighted mean of the mode's particles and
// the covariance of the whole set about it.

#include <Eigen/Core>

#include "localizer/filter/particle.hpp"

namespace conicloc::localizer {

using Matrix6 = Eigen::Matrix<double, 6, 6>;
using Vector6 = Eigen::Matrix<double, 6, 1>;

struct PoseEstimateConfig {
  double mode_radius_m = 1.0;  ///< particles this close to the best one form the mode
  double mode_yaw_rad = 30.0 * M_PI / 180.0;  ///< ... and within this heading difference
  /// ... and this height: one place on two identical storeys is two hypotheses, whose mean would
  /// stand between the storeys, in the slab (a stair's flight rises less within mode_radius_m).
  double mode_z_m = 1.0;
};

struct PoseEstimate {
  PoseState state;
  Matrix6 covariance = Matrix6::Zero();  ///< over (x, y, z, roll, pitch, yaw); m², rad²
  double mode_weight = 0.0;              ///< probability mass of the mode's particles
};

/// A pose belongs to the mode about `anchor`: within mode_radius_m in x, y, mode_z_m in z and
/// mode_yaw_rad in yaw.
bool in_mode(const PoseState& state, const PoseState& anchor, const PoseEstimateConfig& config);

/// Which particle the estimate's mode is gathered around.
enum class ModeAnchor {
  HeaviestParticle,  ///< the peak of a tracked cloud (one hypothesis, or one smeared along a
                     ///< corridor, where the best fit to the scan is the best guess)
  /// Of a cloud spread by a global start or a restart (several hypotheses, some of them lone
  /// particles), the particle whose mode holds the most weight:
  /// just after a restart one lone global particle that happens to fit the scan can outweigh
  /// every other particle while the tracked hypothesis, kept as a thousand particles, holds far
  /// more of the probability (the estimate jumped 84 m, to the lone particle, for two scans).
  MostWeight,
};

/// Mean of the particles near the anchor (so a multi-modal cloud during global localisation gives
/// its strongest hypothesis, not a point between hypotheses), with angles averaged on the circle;
/// covariance of all particles about that mean, angle differences wrapped. Precondition:
/// non-empty, normalised log-weights.
PoseEstimate estimate_pose(const ParticleSet& particles, const PoseEstimateConfig& config = {},
                           ModeAnchor anchor = ModeAnchor::HeaviestParticle);

}  // namespace conicloc::localizer
