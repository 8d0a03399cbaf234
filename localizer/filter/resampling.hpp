#pragma once
// Resampling of a weighted particle set: low-variance (systematic) selection and the KLD-sampling
// bound on the number of particles (Fox 2003, "Adapting the sample size in particle filters
// through KLD-sampling").

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "localizer/filter/particle.hpp"

namespace conicloc::localizer {

/// Low-variance resampling (Thrun, Burgard & Fox, Probabilistic Robotics, Table 4.4): `count`
/// equally spaced pointers (u0 + m)/count, m = 0…count−1, walk the cumulative weights once.
/// Each index i is selected ⌊count·w_i⌋ or ⌈count·w_i⌉ times (unbiased: E[copies] = count·w_i
/// when u0 ~ U[0, 1)). Precondition: `normalised_log_weights` sum to one in the linear domain,
/// u0 in [0, 1). Returns the selected indices, ascending.
std::vector<std::size_t> low_variance_resample(std::span<const double> normalised_log_weights,
                                               std::size_t count, double u0);

/// KLD-sampling bound (Fox 2003, eq. 12): the number of samples so that, with probability
/// 1 − δ, the KL divergence between the sample-based and the true posterior stays below
/// `epsilon`, when the samples occupy `occupied_bins` histogram bins:
///   n = (k − 1)/(2ε) · (1 − 2/(9(k − 1)) + sqrt(2/(9(k − 1))) · z_{1−δ})³.
/// `z_quantile` is z_{1−δ}, the upper standard-normal quantile (2.326 for δ = 0.01). Returns 1
/// for k ≤ 1.
std::size_t kld_sample_count(std::size_t occupied_bins, double epsilon, double z_quantile);

/// Histogram bin sizes of the KLD bound over (x, y, yaw).
struct KldBins {
  double xy_m = 0.5;
  double yaw_rad = 10.0 * 3.14159265358979323846 / 180.0;
  double z_m = 1.0;  ///< separates storeys
  /// Without odometry the particles' velocities are part of the state (MotionModel), and a cloud
  /// spread over velocities needs particles for each; with odometry they are all equal and add
  /// no bins.
  double velocity_m_s = 0.25;
};

/// The (x, y, z, yaw, forward and left velocity) bin of `particle`, packed into one key.
std::uint64_t kld_bin_key(const Particle& particle, const KldBins& bins);

/// Number of distinct (x, y, z, yaw, forward and left velocity) bins occupied by the particles
/// at `indices`.
std::size_t count_occupied_bins(const ParticleSet& particles, std::span<const std::size_t> indices,
                                const KldBins& bins);

}  // namespace conicloc::localizer
