#pragma once
// How finely a particle cloud samples the pose space, as the range error it leaves unresolved.
//
// A particle stands for the poses nearer to it than to any other particle. In a sparse cloud (a
// global start, a recovery) the likelihood at the particle's own pose ranks it by luck: with
// σ = 5 cm, a particle 0.3 m from the truth explains less of the scan than a particle sitting on a
// look-alike place, and the cloud converges there. Its weight should be the likelihood averaged
// over the poses it stands for; to first order that is the likelihood with every range residual
// widened by the range error those poses cause,
//   σ_eff² = σ² + b²,  b = d,
// d the median distance from a particle to its nearest neighbour: in a cloud spread at random
// the truth is as far from its nearest particle as a particle is from its own nearest neighbour
// (the same Poisson nearest-neighbour distribution), so that is the offset the likelihood must
// forgive. d is measured in the space (x, y, z, r̄·cos ψ, r̄·sin ψ), where a yaw offset δψ moves a
// return at the scan's median range r̄ by r̄·δψ (the chord 2r̄·sin(δψ/2)). As the cloud concentrates,
// d and b shrink: coarse to fine, like the levels of a map pyramid, driven by the cloud itself. The
// widening is shared by every term of the scan (one pose error for all beams), so it also raises
// their correlation (correlated_terms.hpp): RangeNoise's shared_sigma_m grows alike.

#include "localizer/filter/particle.hpp"
#include "sensor/scan.hpp"

namespace conicloc::localizer {

/// Median range of the scan's valid returns (m); 0 for a scan without any.
double median_range_m(const sensor::Scan& scan);

/// b = the median distance from a particle to its nearest other particle in
/// (x, y, z, r̄·cos ψ, r̄·sin ψ), r̄ = `range_m` (metres). 0 for fewer than two particles.
double cloud_pose_blur_m(const ParticleSet& particles, double range_m);

}  // namespace conicloc::localizer
