#pragma once
// The velocity each particle's Ornstein–Uhlenbeck process reverts to (MotionModel::
// predict_velocity) while a cloud spread by a global start or a recovery holds several places.
//
// Why: one mean over such a cloud mixes hypotheses. A recovery's new particles start at rest
// (MotionModel::draw_initial_velocity) and hold the cloud's weighted mean near zero, so the
// particles on the true place were pulled toward rest by a share 1 − e^(−dt/T) of their speed
// per scan while the scans, tempered to keep half the cloud effective, pushed them toward the
// sensor's. PNU, kidnap without odometry, seed 5: the restart found the place 0.7 s later, then its
// cloud moved at 0.4 m/s against the sensor's 1 m/s and was 8 m behind at 14 s, never settling.
// Each hypothesis is a sensor moving at its own speed; its particles revert to the weighted mean
// of that hypothesis alone.
//
// The hypotheses are the cloud's modes as find_modes() gathers them (the particles within the
// filter's mode radius, height and heading of the heaviest particle not yet in one), at most
// `max_modes` of them. Right after a resampling every weight is equal and the anchors come in the
// particles' order, so the modes are then local groups of the cloud rather than its heaviest
// places; either way no particle is pulled toward the velocity of a place it is not at. A
// particle in none stands for a hypothesis of its own and reverts to its own velocity. Cost
// O(max_modes · N) per scan, and only while such a cloud searches.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "localizer/filter/particle.hpp"
#include "localizer/filter/pose_estimate.hpp"

namespace conicloc::localizer {

/// Per particle, the weighted mean (forward, left in m/s, yaw rate in rad/s) of the velocities of
/// its mode's particles, or its own velocity when it is in none of the `max_modes` modes found.
/// Precondition: normalised log-weights.
std::vector<Eigen::Vector3d> hypothesis_velocities(const ParticleSet& particles,
                                                   const PoseEstimateConfig& mode,
                                                   std::size_t max_modes);

}  // namespace conicloc::localizer
