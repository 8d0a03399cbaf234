#include "localizer/filter/heading_proposal.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "localizer/conic/pose.hpp"
#include "localizer/filter/range_profile.hpp"

namespace conicloc::localizer {

namespace {

/// A circular histogram of directions over [0, π).
class DirectionHistogram {
 public:
  explicit DirectionHistogram(double bin_rad)
      : bins_(static_cast<std::size_t>(std::max(1.0, std::round(M_PI / bin_rad))), 0.0) {}

  /// Bin b holds the directions within half a bin of b·π/n.
  void add(double angle_rad, double weight) {
    const auto n = static_cast<long>(bins_.size());
    const long bin = std::lround(angle_rad / M_PI * static_cast<double>(n));
    bins_[static_cast<std::size_t>((bin % n + n) % n)] += weight;
  }

  /// Smoothed by a triangular kernel over ±2 bins: a wall measured 1° off still adds to its bin.
  std::vector<double> smoothed() const {
    const int n = static_cast<int>(bins_.size());
    std::vector<double> out(bins_.size(), 0.0);
    for (int b = 0; b < n; ++b) {
      for (int k = -2; k <= 2; ++k) {
        out[static_cast<std::size_t>(b)] +=
            (3 - std::abs(k)) * bins_[static_cast<std::size_t>(((b + k) % n + n) % n)];
      }
    }
    return out;
  }

  /// The angle of bin b, refined by a parabola through it and its neighbours.
  double peak_angle(const std::vector<double>& h, std::size_t b) const {
    const std::size_t n = h.size();
    const double left = h[(b + n - 1) % n], mid = h[b], right = h[(b + 1) % n];
    const double curvature = left - 2.0 * mid + right;
    const double offset = curvature < 0.0 ? 0.5 * (left - right) / curvature : 0.0;
    double a = (static_cast<double>(b) + offset) * M_PI / static_cast<double>(n);
    a = std::fmod(a, M_PI);
    return a < 0.0 ? a + M_PI : a;
  }

 private:
  std::vector<double> bins_;
};

}  // namespace

std::vector<double> map_wall_directions(const maps::PlaneMap& map,
                                        const HeadingProposalConfig& config) {
  DirectionHistogram histogram(config.bin_rad);
  for (const maps::PlanarPolygon& polygon : map.polygons) {
    if (polygon.kind != maps::SurfaceKind::Wall) continue;
    // Horizontal length of the wall: what a spinning sensor's rings see of it.
    const double height = std::max(polygon.bounds.sizes().z(), 0.1);
    const Eigen::Vector3d& n = polygon.plane.normal;
    histogram.add(std::atan2(n.y(), n.x()), polygon.area / height);
  }
  const std::vector<double> h = histogram.smoothed();
  const double strongest = *std::max_element(h.begin(), h.end());
  if (!(strongest > 0.0)) return {};
  std::vector<std::size_t> peaks;
  const std::size_t n = h.size();
  for (std::size_t b = 0; b < n; ++b) {
    const double left = h[(b + n - 1) % n], right = h[(b + 1) % n];
    // ">=" on one side only: a flat top of two equal bins gives one peak.
    if (h[b] > left && h[b] >= right && h[b] >= config.map_peak_fraction * strongest)
      peaks.push_back(b);
  }
  std::sort(peaks.begin(), peaks.end(), [&](std::size_t a, std::size_t b) { return h[a] > h[b]; });
  if (peaks.size() > config.max_map_directions) peaks.resize(config.max_map_directions);
  std::vector<double> directions;
  for (const std::size_t b : peaks) directions.push_back(histogram.peak_angle(h, b));
  return directions;
}

std::optional<double> scan_wall_direction(const sensor::Scan& scan,
                                          const HeadingProposalConfig& config) {
  DirectionHistogram histogram(config.bin_rad);
  double total = 0.0;
  for (const std::vector<Eigen::Vector2d>& ring : ring_points(scan)) {
    // Returns are in azimuth order: the chord from each return to the first one at least
    // min_chord_m further on lies along the surface both hit, unless they are on two (then it
    // is longer than max_chord_m or crosses a corner, a minority).
    std::size_t j = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      j = std::max(j, i + 1);
      while (j < ring.size() && (ring[j] - ring[i]).norm() < config.min_chord_m) ++j;
      if (j >= ring.size()) break;
      const Eigen::Vector2d chord = ring[j] - ring[i];
      if (chord.norm() > config.max_chord_m) continue;
      // Each return stands for range × (azimuth step) of wall: weighted by its range, every
      // metre of wall counts the same, near or far.
      const double weight = ring[i].norm();
      // The normal is the chord turned by 90°.
      histogram.add(std::atan2(chord.y(), chord.x()) + M_PI / 2.0, weight);
      total += weight;
    }
  }
  if (!(total > 0.0)) return std::nullopt;
  const std::vector<double> h = histogram.smoothed();
  const auto peak = static_cast<std::size_t>(std::max_element(h.begin(), h.end()) - h.begin());
  const double mean = std::accumulate(h.begin(), h.end(), 0.0) / static_cast<double>(h.size());
  if (h[peak] < config.min_peak_ratio * mean) return std::nullopt;
  return histogram.peak_angle(h, peak);
}

HeadingProposal::HeadingProposal(std::vector<double> headings, double sigma_rad,
                                 double uniform_fraction)
    : headings_(std::move(headings)),
      sigma_rad_(sigma_rad),
      uniform_fraction_(headings_.empty() ? 1.0 : std::clamp(uniform_fraction, 0.0, 1.0)) {}

HeadingProposal HeadingProposal::from_scan(const std::vector<double>& map_directions,
                                           const sensor::Scan& scan,
                                           const HeadingProposalConfig& config) {
  const std::optional<double> seen = scan_wall_direction(scan, config);
  if (!seen || map_directions.empty()) return {};
  std::vector<double> headings;
  for (const double direction : map_directions) {
    const double yaw = angle_difference(direction - *seen, 0.0);
    headings.push_back(yaw);
    headings.push_back(angle_difference(yaw + M_PI, 0.0));
  }
  return HeadingProposal(std::move(headings), config.sigma_rad, config.uniform_fraction);
}

double HeadingProposal::draw(std::mt19937_64& rng) const {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  if (headings_.empty() || unit(rng) < uniform_fraction_) return -M_PI + 2.0 * M_PI * unit(rng);
  std::uniform_int_distribution<std::size_t> pick(0, headings_.size() - 1);
  std::normal_distribution<double> noise(0.0, sigma_rad_);
  return angle_difference(headings_[pick(rng)] + noise(rng), 0.0);
}

namespace {

// `count` headings evenly round the turn from a uniform offset, into out[first, first + count).
// The offset spans the whole turn: every slot's heading is uniform, not only the first's.
void uniform_star(std::size_t first, std::size_t count, std::mt19937_64& rng,
                  std::vector<double>& out) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double offset = -M_PI + 2.0 * M_PI * unit(rng);
  for (std::size_t j = 0; j < count; ++j) {
    out[first + j] = angle_difference(
        offset + 2.0 * M_PI * static_cast<double>(j) / static_cast<double>(count), 0.0);
  }
}

}  // namespace

std::vector<double> HeadingProposal::draw_spread(std::size_t count, std::mt19937_64& rng) const {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<double> drawn(count);
  if (count == 0) return drawn;
  if (headings_.empty() || unit(rng) < uniform_fraction_) {
    uniform_star(0, count, rng, drawn);
    return drawn;
  }
  std::uniform_int_distribution<std::size_t> pick(0, headings_.size() - 1);
  std::normal_distribution<double> noise(0.0, sigma_rad_);
  const std::size_t start = pick(rng);
  const std::size_t spread = std::min(count, headings_.size());
  for (std::size_t j = 0; j < spread; ++j) {
    const std::size_t k = (start + j * headings_.size() / spread) % headings_.size();
    drawn[j] = angle_difference(headings_[k] + noise(rng), 0.0);
  }
  // More siblings than proposed headings: the rest are a uniform star of their own (a twin of a
  // proposed heading would stand for the same pose).
  if (spread < count) uniform_star(spread, count - spread, rng, drawn);
  return drawn;
}

}  // namespace conicloc::localizer
