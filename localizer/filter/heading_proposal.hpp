#pragma once
// Where a global start or a recovery draws its particles' headings: the scan itself says which
// ones align its walls with the map's. A vertical wall with horizontal normal angle α_s in the
// sensor frame is the map wall at angle α_m when the sensor's yaw is
//   ψ = α_m − α_s  (mod π),
// so with the map's few dominant wall directions {α_m} (a Manhattan building has two) and the
// scan's strongest one, the heading is one of a handful of values ψ, ψ + π per map direction
// instead of anywhere in 2π: the same particles sample the pose space tens of times more densely
// where the truth can be (a data-driven proposal, the "dual" samples of Mixture MCL, Thrun et al.
// 2001). Part of the draws stay uniform, so a scan whose strongest direction is clutter, or a
// wall absent from the map, cannot exclude the true heading.

#include <optional>
#include <random>
#include <vector>

#include "maps/plane_map.hpp"
#include "sensor/scan.hpp"

namespace conicloc::localizer {

struct HeadingProposalConfig {
  double bin_rad = M_PI / 180.0;  ///< histogram bin of directions over [0, π)
  /// A scan's wall direction is measured along chords between two returns of one ring this far
  /// apart: long enough that 3 cm of range noise tilts a chord by ≤ 3.5°, short enough to stay
  /// on one wall in a room.
  double min_chord_m = 0.5;
  double max_chord_m = 1.0;
  /// The scan's strongest direction counts where its smoothed bin holds at least this many times
  /// the histogram's mean (a floor's ring circles spread evenly over all directions).
  double min_peak_ratio = 3.0;
  /// Map directions: local maxima of the wall-length histogram holding at least this fraction of
  /// the strongest one, at most `max_map_directions` of them.
  double map_peak_fraction = 0.25;
  std::size_t max_map_directions = 8;
  double sigma_rad = 2.0 * M_PI / 180.0;  ///< spread of a draw about a proposed heading
  double uniform_fraction = 0.5;          ///< share of the draws uniform over [−π, π)
};

/// The dominant wall normal directions of the map, as angles in [0, π) about z, strongest first:
/// a histogram of the vertical surfaces' normals weighted by their horizontal length.
std::vector<double> map_wall_directions(const maps::PlaneMap& map,
                                        const HeadingProposalConfig& config = {});

/// The scan's strongest wall normal direction in the sensor frame, in [0, π); nothing where no
/// direction stands out (HeadingProposalConfig::min_peak_ratio).
std::optional<double> scan_wall_direction(const sensor::Scan& scan,
                                          const HeadingProposalConfig& config = {});

/// A mixture over headings: with probability `uniform_fraction` uniform over [−π, π), else one of
/// `headings` (equally likely) plus Gaussian noise of std. dev. `sigma_rad`.
class HeadingProposal {
 public:
  HeadingProposal() = default;  ///< uniform
  HeadingProposal(std::vector<double> headings, double sigma_rad, double uniform_fraction);

  /// From the map's wall directions and the scan: ψ = α_m − α_s and ψ + π for every map
  /// direction α_m; uniform where the scan shows no direction.
  static HeadingProposal from_scan(const std::vector<double>& map_directions,
                                   const sensor::Scan& scan,
                                   const HeadingProposalConfig& config = {});

  double draw(std::mt19937_64& rng) const;
  /// `count` headings for poses at one position, kept apart: with probability `uniform_fraction`
  /// a star of `count` headings evenly round the turn from a uniform offset, else the proposed
  /// headings spread over the list from a uniform start, each with its own noise (a Manhattan
  /// scan's four when `count` is four). Each is a draw of the mixture, but for siblings beyond
  /// the proposed headings' number, which take a uniform star of their own: siblings apart stand
  /// for poses apart (a cloud's nearest neighbours, pose_blur.hpp, stay at other positions).
  std::vector<double> draw_spread(std::size_t count, std::mt19937_64& rng) const;
  const std::vector<double>& headings() const { return headings_; }

 private:
  std::vector<double> headings_;
  double sigma_rad_ = 0.0;
  double uniform_fraction_ = 1.0;
};

}  // namespace conicloc::localizer
