#include "localizer/conic/ring_envelope.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace conicloc::localizer {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
using Arc = PredictionWorkspace::Arc;

// Roots in (t0, t1) of α cos θ + β sin θ + γ = 0 (where conics i and j swap order).
void switch_points(const Arc& i, const Arc& j, double t0, double t1, std::vector<double>& out) {
  const double alpha = i.a - j.a, beta = i.b - j.b, gamma = i.c - j.c;
  const double radius_sq = alpha * alpha + beta * beta;
  if (!(radius_sq > 0.0) || gamma * gamma >= radius_sq) return;  // never swap (or coincide)
  const double psi = std::atan2(beta, alpha);
  const double delta = std::acos(-gamma / std::sqrt(radius_sq));
  for (double theta : {psi - delta, psi + delta}) {
    theta = std::fmod(theta, kTwoPi);
    if (theta < 0.0) theta += kTwoPi;
    if (theta > t0 && theta < t1) out.push_back(theta);
  }
}

// Index into `active` of the arc with the largest 1/r (nearest surface) at θ.
int nearest_at(const std::vector<Arc>& arcs, const std::vector<int>& active, double theta) {
  const double cos_t = std::cos(theta), sin_t = std::sin(theta);
  int best = active.front();
  double best_inverse = -1.0;
  for (const int k : active) {
    const double inverse = arcs[k].a * cos_t + arcs[k].b * sin_t + arcs[k].c;
    if (inverse > best_inverse) {
      best_inverse = inverse;
      best = k;
    }
  }
  return best;
}

// Whether the direction (x, y) lies in the azimuth interval [t0, t1] of length below π given by
// its end directions d0, d1 (cross products; no trigonometry). Inclusive, as bounds must be.
bool direction_within(double x, double y, double c0, double s0, double c1, double s1) {
  return c0 * y - s0 * x >= 0.0 && x * s1 - y * c1 >= 0.0;
}

// Keeps in `active` only the arcs that can be nearest somewhere in [t0, t1]: an arc whose largest
// 1/r there is below another arc's smallest 1/r there never wins. Bounds of
// f(θ) = a cos θ + b sin θ + c = R cos(θ − ψ) + c: its values at the ends, and c ± R where the
// interval may hold ψ (maximum) or ψ + π (minimum); a margin keeps the test conservative.
void prune_dominated(const std::vector<Arc>& arcs, double t0, double t1, std::vector<int>& active,
                     std::vector<double>& upper) {
  const double c0 = std::cos(t0), s0 = std::sin(t0), c1 = std::cos(t1), s1 = std::sin(t1);
  const bool short_interval = t1 - t0 < 3.0;  // < π: the cross-product test applies
  double best_lower = -std::numeric_limits<double>::infinity();
  upper.resize(active.size());
  for (std::size_t k = 0; k < active.size(); ++k) {
    const Arc& arc = arcs[static_cast<std::size_t>(active[k])];
    const double f0 = arc.a * c0 + arc.b * s0 + arc.c;
    const double f1 = arc.a * c1 + arc.b * s1 + arc.c;
    const double radius = std::sqrt(arc.a * arc.a + arc.b * arc.b);
    const bool may_hold_max = !short_interval || direction_within(arc.a, arc.b, c0, s0, c1, s1);
    const bool may_hold_min = !short_interval || direction_within(-arc.a, -arc.b, c0, s0, c1, s1);
    upper[k] = may_hold_max ? arc.c + radius : std::max(f0, f1);
    const double lower = may_hold_min ? arc.c - radius : std::min(f0, f1);
    best_lower = std::max(best_lower, lower);
  }
  const double margin = 1e-9 * std::abs(best_lower);
  std::size_t kept = 0;
  for (std::size_t k = 0; k < active.size(); ++k) {
    if (upper[k] >= best_lower - margin) active[kept++] = active[k];
  }
  active.resize(kept);
}

}  // namespace

void build_ring_envelope(std::vector<Arc>& arcs, PredictionWorkspace& workspace,
                         PredictedRing& out) {
  out.clear();
  std::sort(arcs.begin(), arcs.end(),
            [](const Arc& x, const Arc& y) { return x.begin_rad < y.begin_rad; });
  std::vector<double>& events = workspace.events;
  events.clear();
  events.push_back(0.0);
  events.push_back(kTwoPi);
  for (const Arc& arc : arcs) {
    events.push_back(arc.begin_rad);
    events.push_back(arc.end_rad);
  }
  std::sort(events.begin(), events.end());
  events.erase(std::unique(events.begin(), events.end()), events.end());

  std::vector<int>& active = workspace.active;
  active.clear();
  std::vector<double>& splits = workspace.splits;
  std::size_t next_arc = 0;
  for (std::size_t e = 0; e + 1 < events.size(); ++e) {
    const double t0 = events[e], t1 = events[e + 1];
    // Active arcs cover all of [t0, t1]: arcs start and end only at events.
    std::erase_if(active, [&](int k) { return arcs[k].end_rad <= t0; });
    while (next_arc < arcs.size() && arcs[next_arc].begin_rad <= t0) {
      if (arcs[next_arc].end_rad > t0) active.push_back(static_cast<int>(next_arc));
      ++next_arc;
    }
    if (active.empty()) {
      out.append(t1, 0.0, 0.0, 0.0, -1);
      continue;
    }
    if (active.size() == 1) {
      const Arc& arc = arcs[active.front()];
      out.append(t1, arc.a, arc.b, arc.c, arc.polygon);
      continue;
    }
    // Only arcs that can win somewhere in [t0, t1] take part (the active set itself is kept).
    std::vector<int>& contenders = workspace.contenders;
    contenders.assign(active.begin(), active.end());
    prune_dominated(arcs, t0, t1, contenders, workspace.bounds);
    if (contenders.size() == 1) {
      const Arc& arc = arcs[static_cast<std::size_t>(contenders.front())];
      out.append(t1, arc.a, arc.b, arc.c, arc.polygon);
      continue;
    }
    splits.clear();
    for (std::size_t i = 0; i < contenders.size(); ++i) {
      for (std::size_t j = i + 1; j < contenders.size(); ++j) {
        switch_points(arcs[contenders[i]], arcs[contenders[j]], t0, t1, splits);
      }
    }
    splits.push_back(t1);
    std::sort(splits.begin(), splits.end());
    double begin = t0;
    for (const double end : splits) {
      if (!(end > begin)) continue;
      const Arc& arc = arcs[nearest_at(arcs, contenders, 0.5 * (begin + end))];
      out.append(end, arc.a, arc.b, arc.c, arc.polygon);
      begin = end;
    }
  }
}

}  // namespace conicloc::localizer
