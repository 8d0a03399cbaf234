#include "localizer/models/segment_landmarks.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace conicloc::localizer {
namespace {

// vᵀ S w for a symmetric S stored as its upper triangle.
double bilinear(const double s[6], const double v[3], const double w[3]) {
  return v[0] * (s[0] * w[0] + s[1] * w[1] + s[2] * w[2]) +
         v[1] * (s[1] * w[0] + s[3] * w[1] + s[4] * w[2]) +
         v[2] * (s[2] * w[0] + s[4] * w[1] + s[5] * w[2]);
}

// S·v for a symmetric S stored as its upper triangle.
void multiply(const double s[6], const double v[3], double out[3]) {
  out[0] = s[0] * v[0] + s[1] * v[1] + s[2] * v[2];
  out[1] = s[1] * v[0] + s[3] * v[1] + s[4] * v[2];
  out[2] = s[2] * v[0] + s[4] * v[1] + s[5] * v[2];
}

// A point a little inside the span, so a check does not sit on the polygon's edge.
double inset(const SegmentFit& fit, double fraction) {
  return fit.begin_rad + fraction * (fit.end_rad - fit.begin_rad);
}

// Orders the terms by landmark (counting sort, stable), renumbers the segments' terms, and lays
// the fits' coefficients out as columns in that order; every term starts checked.
void order_terms_by_landmark(const std::vector<CandidateTerm>& fit_terms, Association& out) {
  const std::size_t landmarks = out.landmarks.size(), count = out.terms.size();
  out.landmark_terms.assign(landmarks + 1, 0);
  for (const AssociatedTerm& term : out.terms) ++out.landmark_terms[term.landmark + 1];
  for (std::size_t l = 0; l < landmarks; ++l) out.landmark_terms[l + 1] += out.landmark_terms[l];
  std::vector<int> next(out.landmark_terms.begin(), out.landmark_terms.end() - 1);
  std::vector<int> position(count);
  std::vector<AssociatedTerm> ordered(count);
  for (std::size_t t = 0; t < count; ++t) {
    position[t] = next[static_cast<std::size_t>(out.terms[t].landmark)]++;
    ordered[static_cast<std::size_t>(position[t])] = out.terms[t];
  }
  out.terms.swap(ordered);
  for (LandmarkSegment& segment : out.segments) {
    for (int k = 0; k < segment.candidate_count; ++k) {
      segment.terms[k] = position[static_cast<std::size_t>(segment.terms[k])];
    }
  }
  out.quadratic.resize(static_cast<Eigen::Index>(count), 10);
  out.vertical_offset_m.resize(static_cast<Eigen::Index>(count));
  out.checked_terms.resize(count);
  for (std::size_t t = 0; t < count; ++t) {
    const CandidateTerm& term = fit_terms[static_cast<std::size_t>(out.terms[t].fit)];
    const auto row = static_cast<Eigen::Index>(t);
    for (int i = 0; i < 10; ++i) out.quadratic(row, i) = term.quadratic[i];
    out.vertical_offset_m(row) = term.vertical_offset_m;
    out.checked_terms[t] = static_cast<int>(t);
  }
}

}  // namespace

SegmentFit make_segment_fit(const sensor::RingScan& ring_scan, const ConicSegment& segment,
                            int ring, double min_range_m, double max_range_m) {
  SegmentFit fit;
  fit.ring = ring;
  fit.begin_rad = segment.begin_rad;
  fit.end_rad = segment.end_rad;
  fit.p[0] = segment.a;
  fit.p[1] = segment.b;
  fit.p[2] = segment.c;
  const std::size_t n = ring_scan.returns.size();
  if (n == 0 || segment.first >= n || segment.last >= n) return fit;
  for (std::size_t i = segment.first;; i = (i + 1) % n) {
    const sensor::Return& ret = ring_scan.returns[i];
    if (ret.status == sensor::ReturnStatus::Valid && ret.range_m >= min_range_m &&
        ret.range_m <= max_range_m) {
      const double r2 = ret.range_m * ret.range_m, w = r2 * r2;
      const double x[3] = {std::cos(ret.azimuth_rad), std::sin(ret.azimuth_rad), 1.0};
      fit.moments[0] += w * x[0] * x[0];
      fit.moments[1] += w * x[0] * x[1];
      fit.moments[2] += w * x[0];
      fit.moments[3] += w * x[1] * x[1];
      fit.moments[4] += w * x[1];
      fit.moments[5] += w;
      fit.returns += 1.0;
    }
    if (i == segment.last) break;
  }
  return fit;
}

double squared_range_difference(const SegmentFit& fit, const double p[3]) {
  const double d[3] = {p[0] - fit.p[0], p[1] - fit.p[1], p[2] - fit.p[2]};
  return std::max(0.0, bilinear(fit.moments, d, d));
}

// K' = LᵀKL, with w = L u mapping the plane u = (n_s, D_s) to
// (n', E) = (cos φ n_x, cos φ n_y, sin φ n_z, −o n_z − D_s).
CandidateTerm candidate_term(const SegmentFit& fit, const RingGeometry& geometry) {
  const double* m = fit.moments;
  double g[3];
  multiply(m, fit.p, g);
  Eigen::Matrix4d K;
  K << m[0], m[1], m[2], -g[0],  //
      m[1], m[3], m[4], -g[1],   //
      m[2], m[4], m[5], -g[2],   //
      -g[0], -g[1], -g[2], fit.p[0] * g[0] + fit.p[1] * g[1] + fit.p[2] * g[2];
  Eigen::Matrix4d L = Eigen::Matrix4d::Zero();
  L(0, 0) = geometry.cos_elevation;
  L(1, 1) = geometry.cos_elevation;
  L(2, 2) = geometry.sin_elevation;
  L(3, 2) = -geometry.vertical_offset_m;
  L(3, 3) = -1.0;
  const Eigen::Matrix4d quadratic = L.transpose() * K * L;
  CandidateTerm term;
  int next = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = i; j < 4; ++j) term.quadratic[next++] = (i == j ? 1.0 : 2.0) * quadratic(i, j);
  }
  const double checks[3] = {inset(fit, 0.05), inset(fit, 0.5), inset(fit, 0.95)};
  for (int c = 0; c < 3; ++c) {
    term.checks[3 * c] = geometry.cos_elevation * std::cos(checks[c]);
    term.checks[3 * c + 1] = geometry.cos_elevation * std::sin(checks[c]);
    term.checks[3 * c + 2] = geometry.sin_elevation;
  }
  term.vertical_offset_m = geometry.vertical_offset_m;
  return term;
}

void associate_segments(const std::vector<SegmentFit>& fits,
                        const std::vector<CandidateTerm>& fit_terms, const PredictedScan& predicted,
                        const maps::PlaneMap& map, double gate_m, Association& out) {
  out.landmarks.clear();
  out.segments.clear();
  out.terms.clear();
  out.unassociated_segments = 0;
  out.unassociated_returns = 0.0;
  constexpr double kSampleFractions[] = {-0.2, 0.0, 0.2, 0.4, 0.6, 0.8, 1.0, 1.2};
  constexpr int kSamples = static_cast<int>(std::size(kSampleFractions));
  std::vector<int> landmark_of_polygon(map.polygons.size(), -1);
  for (std::size_t f = 0; f < fits.size(); ++f) {
    const SegmentFit& fit = fits[f];
    const PredictedRing& ring = predicted.ring(fit.ring);
    std::pair<double, int> found[kSamples];  // (cost, polygon)
    int found_count = 0;
    for (const double fraction : kSampleFractions) {
      if (ring.piece_count() == 0 || !(fit.returns > 0.0)) break;
      const std::size_t piece = ring.piece_at(inset(fit, fraction));
      const int polygon = ring.polygon[piece];
      if (polygon < 0) continue;
      bool seen = false;
      for (int k = 0; k < found_count; ++k) seen |= found[k].second == polygon;
      if (seen) continue;
      const double p[3] = {ring.a[piece], ring.b[piece], ring.c[piece]};
      const double cost = squared_range_difference(fit, p);
      if (std::sqrt(cost / fit.returns) <= gate_m) found[found_count++] = {cost, polygon};
    }
    if (found_count == 0) {
      ++out.unassociated_segments;
      out.unassociated_returns += fit.returns;
      continue;
    }
    // Best first (insertion sort: a handful of entries).
    for (int k = 1; k < found_count; ++k) {
      for (int j = k; j > 0 && found[j] < found[j - 1]; --j) std::swap(found[j], found[j - 1]);
    }
    LandmarkSegment segment;
    for (int k = 0; k < found_count && k < LandmarkSegment::kMaxCandidates; ++k) {
      const int polygon = found[k].second;
      int& landmark = landmark_of_polygon[static_cast<std::size_t>(polygon)];
      if (landmark < 0) {
        landmark = static_cast<int>(out.landmarks.size());
        Landmark added;
        added.polygon = polygon;
        const maps::Plane& plane = map.polygons[static_cast<std::size_t>(polygon)].plane;
        for (int i = 0; i < 3; ++i) added.normal_map[i] = plane.normal[i];
        added.offset_map = plane.offset;
        out.landmarks.push_back(added);
      }
      segment.candidates[segment.candidate_count++] = landmark;
    }
    segment.returns = fit.returns;
    segment.inverse_returns = 1.0 / fit.returns;
    for (int k = 0; k < segment.candidate_count; ++k) {
      segment.terms[k] = static_cast<int>(out.terms.size());
      out.terms.push_back({static_cast<int>(f), segment.candidates[k]});
    }
    out.segments.push_back(segment);
  }
  order_terms_by_landmark(fit_terms, out);
}

void mark_seen_throughout_cell(Association& association,
                               const std::vector<CandidateTerm>& fit_terms, const Pose3& centre,
                               double translation_m, double rotation_rad, double min_inverse,
                               double max_inverse) {
  // Rounding slack on top of the geometric margins.
  constexpr double kSlack = 1e-9;
  std::vector<SensorPlaneTerms> planes;  // per landmark, at the centre
  planes.reserve(association.landmarks.size());
  for (const Landmark& landmark : association.landmarks) {
    planes.push_back(landmark_plane_terms(landmark, centre));
  }
  for (AssociatedTerm& associated : association.terms) {
    const CandidateTerm& term = fit_terms[static_cast<std::size_t>(associated.fit)];
    const double* u = planes[static_cast<std::size_t>(associated.landmark)].u;
    const double E = -(u[3] + term.vertical_offset_m * u[2]);
    const double normal_margin = rotation_rad + kSlack;
    const double E_margin =
        translation_m + std::abs(term.vertical_offset_m) * rotation_rad + kSlack;
    // |E| > E_margin keeps E's sign over the cell; then, with v = sign(E) x_c·n_s,
    // v − δ_R > min_inverse (|E| + ΔE) and v + δ_R ≤ max_inverse (|E| − ΔE) at every check.
    bool seen = std::abs(E) > E_margin;
    const double sign = E < 0.0 ? -1.0 : 1.0;
    for (int c = 0; c < 3 && seen; ++c) {
      const double* x = &term.checks[3 * c];
      const double v = sign * (x[0] * u[0] + x[1] * u[1] + x[2] * u[2]);
      seen = v - normal_margin > min_inverse * (std::abs(E) + E_margin) &&
             v + normal_margin <= max_inverse * (std::abs(E) - E_margin);
    }
    associated.check_visibility = !seen;
  }
  association.checked_terms.clear();
  for (std::size_t term = 0; term < association.terms.size(); ++term) {
    if (association.terms[term].check_visibility)
      association.checked_terms.push_back(static_cast<int>(term));
  }
}

void candidate_costs(const Association& association, const std::vector<CandidateTerm>& fit_terms,
                     const std::vector<SensorPlaneTerms>& planes, double min_inverse,
                     double max_inverse, Eigen::ArrayXd& costs) {
  costs.resize(static_cast<Eigen::Index>(association.terms.size()));
  for (std::size_t l = 0; l + 1 < association.landmark_terms.size(); ++l) {
    const Eigen::Index begin = association.landmark_terms[l];
    const Eigen::Index count = association.landmark_terms[l + 1] - begin;
    if (count == 0) continue;
    // E² cost = Σ_i k_i m_i over the landmark's terms, with its plane's monomials m_i fixed, and
    // E = −(D_s + o n_z): one expression, evaluated as one vectorised loop by Eigen.
    const SensorPlaneTerms& plane = planes[l];
    const double* m = plane.monomials;
    const auto k = association.quadratic.middleRows(begin, count);
    const auto E = -(plane.u[3] + association.vertical_offset_m.segment(begin, count) * plane.u[2]);
    costs.segment(begin, count) =
        ((k.col(0) * m[0] + k.col(1) * m[1] + k.col(2) * m[2] + k.col(3) * m[3] + k.col(4) * m[4] +
          k.col(5) * m[5] + k.col(6) * m[6] + k.col(7) * m[7] + k.col(8) * m[8] + k.col(9) * m[9]) /
         E.square())
            .max(0.0);
  }
  for (const int t : association.checked_terms) {
    const AssociatedTerm& associated = association.terms[static_cast<std::size_t>(t)];
    if (!candidate_visible(fit_terms[static_cast<std::size_t>(associated.fit)],
                           planes[static_cast<std::size_t>(associated.landmark)].u, min_inverse,
                           max_inverse)) {
      costs(t) = std::numeric_limits<double>::infinity();
    }
  }
}

}  // namespace conicloc::localizer
