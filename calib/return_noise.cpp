#include "calib/return_noise.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "localizer/filter/median.hpp"

namespace conicloc::calib {
namespace {

// One bin's robust variance of the residuals, against the mean of its u = 1/c².
struct Bin {
  double u = 0.0;
  double variance = 0.0;
  double count = 0.0;
};

// Consistency of the MAD for Gaussian noise: σ = 1.4826·MAD.
constexpr double kMadToSigma = 1.4826;
// A variance below (1 µm)² is taken as that: the weights n/V² stay finite on noise-free data.
constexpr double kMinVariance = 1e-12;

struct Line {
  double intercept = 0.0;  ///< σ_r²
  double slope = 0.0;      ///< σ_s²
};

// The residuals' variance at u = 1/c² under `line`, floored.
double variance(const Line& line, double u) {
  return std::max(kMinVariance, line.intercept + line.slope * u);
}

double weighted_misfit(const std::vector<Bin>& bins, const std::vector<double>& w, Line line) {
  double total = 0.0;
  for (std::size_t b = 0; b < bins.size(); ++b) {
    const double r = bins[b].variance - line.intercept - line.slope * bins[b].u;
    total += w[b] * r * r;
  }
  return total;
}

// min Σ w_b·(V_b − σ_r² − σ_s²·u_b)² with σ_r², σ_s² ≥ 0: the free minimum if it is feasible,
// else the better of the two edges (a convex cost's constrained minimum lies on one).
Line fit_line(const std::vector<Bin>& bins, const std::vector<double>& w) {
  double S = 0, Su = 0, Suu = 0, Sv = 0, Suv = 0;
  for (std::size_t b = 0; b < bins.size(); ++b) {
    S += w[b];
    Su += w[b] * bins[b].u;
    Suu += w[b] * bins[b].u * bins[b].u;
    Sv += w[b] * bins[b].variance;
    Suv += w[b] * bins[b].u * bins[b].variance;
  }
  const double det = S * Suu - Su * Su;
  if (det > 1e-12 * S * Suu) {
    const Line free{(Suu * Sv - Su * Suv) / det, (S * Suv - Su * Sv) / det};
    if (free.intercept >= 0.0 && free.slope >= 0.0) return free;
  }
  const Line range_only{std::max(0.0, Sv / S), 0.0};
  const Line surface_only{0.0, std::max(0.0, Suv / Suu)};
  return weighted_misfit(bins, w, range_only) <= weighted_misfit(bins, w, surface_only)
             ? range_only
             : surface_only;
}

}  // namespace

double ReturnNoise::residual_scale(double cosine) const {
  const double r2 = range_sigma_m * range_sigma_m;
  const double s2 = surface_sigma_m * surface_sigma_m;
  if (!(cosine > 0.0)) return 0.0;
  if (r2 + s2 <= 0.0) return cosine;
  return cosine * std::sqrt((r2 + s2) / (cosine * cosine * r2 + s2));
}

ReturnNoise fit_return_noise(std::span<const double> range_residuals_m,
                             std::span<const double> cosines, const ReturnNoiseConfig& config) {
  if (range_residuals_m.size() != cosines.size()) {
    throw std::invalid_argument("fit_return_noise: " + std::to_string(range_residuals_m.size()) +
                                " residuals but " + std::to_string(cosines.size()) + " cosines");
  }
  const std::size_t n = cosines.size();
  for (std::size_t i = 0; i < n; ++i) {
    // No upper bound: an adjusted plane's gradient n − s_u·e_u − s_v·e_v is a hair over unit.
    if (!(cosines[i] > 0.0 && std::isfinite(cosines[i])) || !std::isfinite(range_residuals_m[i])) {
      throw std::invalid_argument("fit_return_noise: return " + std::to_string(i) + " has cosine " +
                                  std::to_string(cosines[i]) + " and residual " +
                                  std::to_string(range_residuals_m[i]) +
                                  " (a finite cosine > 0 and a finite residual needed)");
    }
  }
  if (config.bins < 2 || config.min_returns < 0 ||
      n < std::max(static_cast<std::size_t>(config.min_returns),
                   2 * static_cast<std::size_t>(config.bins))) {
    return {};
  }
  std::vector<double> u(n);
  for (std::size_t i = 0; i < n; ++i) u[i] = 1.0 / (cosines[i] * cosines[i]);
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return u[a] < u[b]; });

  const auto count = static_cast<std::size_t>(config.bins);
  std::vector<Bin> bins(count);
  for (std::size_t b = 0; b < count; ++b) {
    const std::size_t begin = n * b / count, end = n * (b + 1) / count;
    double u_sum = 0.0;
    for (std::size_t k = begin; k < end; ++k) u_sum += u[order[k]];
    bins[b].u = u_sum / static_cast<double>(end - begin);
    bins[b].count = static_cast<double>(end - begin);
  }
  // Each bin's variance as its MAD gives it, the residuals first divided by their standard
  // deviation under `line` (so a bin spanning u from 16 to 90 is not read as one Gaussian: a
  // mixture of scales has a smaller MAD than its variance says), times the line's at the bin's
  // mean u. With the line unknown (σ 1 everywhere) it is the bin's own MAD.
  std::vector<double> values;
  auto read_bins = [&](const Line& line, bool known) {
    for (std::size_t b = 0; b < count; ++b) {
      const std::size_t begin = n * b / count, end = n * (b + 1) / count;
      values.clear();
      for (std::size_t k = begin; k < end; ++k) {
        const double V = known ? variance(line, u[order[k]]) : 1.0;
        values.push_back(range_residuals_m[order[k]] / std::sqrt(V));
      }
      const double centre = localizer::median_of(values);
      for (double& v : values) v = std::abs(v - centre);
      const double scale = kMadToSigma * localizer::median_of(values);
      bins[b].variance =
          std::max(kMinVariance, scale * scale * (known ? variance(line, bins[b].u) : 1.0));
    }
  };
  // The weights n/V²: first from each bin's own V, then from the line's (a bin that came out low
  // by chance would otherwise pull the line down to it).
  std::vector<double> w(count);
  read_bins({}, false);
  for (std::size_t b = 0; b < count; ++b) w[b] = bins[b].count / std::pow(bins[b].variance, 2);
  Line line = fit_line(bins, w);
  for (int pass = 0; pass < 3; ++pass) {
    read_bins(line, true);
    for (std::size_t b = 0; b < count; ++b)
      w[b] = bins[b].count / std::pow(variance(line, bins[b].u), 2);
    line = fit_line(bins, w);
  }
  return {std::sqrt(line.intercept), std::sqrt(line.slope)};
}

}  // namespace conicloc::calib
