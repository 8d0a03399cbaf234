#include "localizer/conic/occlusion_bins.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace conicloc::localizer {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
constexpr double kBinWidth = kTwoPi / OcclusionBins::kBins;
// Rounding allowance of ranges: covers must beat the nearest point by this much.
constexpr double kRangeSlack = 1e-9;

double wrap_pi(double angle) {
  while (angle > M_PI) angle -= kTwoPi;
  while (angle <= -M_PI) angle += kTwoPi;
  return angle;
}

// The farthest range of the arc 1/r = a cos θ + b sin θ + c (R = |(a, b)|) over a part narrower
// than π: max r = 1 / min(1/r), at the part's ends or where 1/r = R cos(θ − θ₀) + c is least, at
// θ₀ + π, whose direction (−a, −b) lies inside the part when it is counter-clockwise of the
// begin and clockwise of the end. Infinite where 1/r is not positive all over (no bound).
double farthest_m(double a, double b, double c, double R, double cos_begin, double sin_begin,
                  double cos_end, double sin_end) {
  double inverse = std::min(a * cos_begin + b * sin_begin, a * cos_end + b * sin_end) + c;
  if (a * sin_begin - b * cos_begin >= 0.0 && b * cos_end - a * sin_end >= 0.0) {
    inverse = std::min(inverse, c - R);
  }
  return inverse > 0.0 ? 1.0 / inverse : std::numeric_limits<double>::infinity();
}

}  // namespace

AzimuthSpan polygon_azimuth_span(const double* x, const double* y, std::size_t count) {
  AzimuthSpan whole;
  if (count == 0) return whole;
  double extent = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    extent = std::max(extent, std::sqrt(x[i] * x[i] + y[i] * y[i]));
  }
  const double on_axis_m = 1e-9 * std::max(extent, 1.0);
  // Along an edge that misses the z axis the azimuth moves monotonically by less than π, so the
  // unwrapped vertex azimuths bound the projection's; a winding of ±2π means it holds the axis.
  const double first = std::atan2(y[0], x[0]);
  double previous = first, unwrapped = first, lo = first, hi = first;
  for (std::size_t i = 1; i <= count; ++i) {
    const std::size_t v = i % count;
    if (std::sqrt(x[v] * x[v] + y[v] * y[v]) <= on_axis_m) return whole;
    const double azimuth = std::atan2(y[v], x[v]);
    const double step = wrap_pi(azimuth - previous);
    if (std::abs(step) > M_PI - 1e-6) return whole;  // the edge passes (nearly) through the axis
    unwrapped += step;
    lo = std::min(lo, unwrapped);
    hi = std::max(hi, unwrapped);
    previous = azimuth;
  }
  if (std::abs(unwrapped - first) > M_PI) return whole;  // wound once around the axis
  const double width = hi - lo + 2.0 * kAzimuthSlack_rad;
  if (width >= kTwoPi) return whole;
  double begin = std::fmod(lo - kAzimuthSlack_rad, kTwoPi);
  if (begin < 0.0) begin += kTwoPi;
  return {.whole = false, .begin_rad = begin, .width_rad = width};
}

OcclusionBins::OcclusionBins() {
  for (int b = 0; b <= kBins; ++b) {
    cos_edge_[static_cast<std::size_t>(b)] = std::cos(b * kBinWidth);
    sin_edge_[static_cast<std::size_t>(b)] = std::sin(b * kBinWidth);
  }
  reset();
}

void OcclusionBins::reset() {
  cover_m_.fill(std::numeric_limits<double>::infinity());
  for (Bin& bin : bins_) bin.count = 0;
}

void OcclusionBins::cover_bin(int bin, const Segment& part) {
  Bin& current = bins_[static_cast<std::size_t>(bin)];
  double& bound = cover_m_[static_cast<std::size_t>(bin)];
  const bool whole = part.begin_rad <= bin * kBinWidth && part.end_rad >= (bin + 1) * kBinWidth;
  if (whole && current.count == 0) {
    current.segments[0] = part;
    current.count = 1;
    bound = part.farthest_m;
    return;
  }
  // The new partition: at most the old segments, the gaps between them (one more) and the two
  // remainders of the segments the part begins and ends in.
  std::array<Segment, 2 * kSegments + 3> next;
  int count = 0;
  const auto emit = [&](const Segment& segment) {
    if (!(segment.end_rad > segment.begin_rad)) return;
    Segment* last = count > 0 ? &next[static_cast<std::size_t>(count - 1)] : nullptr;
    if (last != nullptr && last->a == segment.a && last->b == segment.b && last->c == segment.c &&
        segment.begin_rad - last->end_rad <= kAzimuthSlack_rad) {
      // One owner on both sides: its farthest over the union is the larger of the two.
      last->end_rad = segment.end_rad;
      last->cos_end = segment.cos_end;
      last->sin_end = segment.sin_end;
      last->farthest_m = std::max(last->farthest_m, segment.farthest_m);
      return;
    }
    next[static_cast<std::size_t>(count++)] = segment;
  };
  // The segment of owner `o` (its coefficients) over [begin, end] (with their cosines and sines).
  const auto owned = [](const Segment& o, double begin, double cos_begin, double sin_begin,
                        double end, double cos_end, double sin_end) {
    Segment segment = o;
    segment.begin_rad = begin;
    segment.cos_begin = cos_begin;
    segment.sin_begin = sin_begin;
    segment.end_rad = end;
    segment.cos_end = cos_end;
    segment.sin_end = sin_end;
    segment.farthest_m = farthest_m(o.a, o.b, o.c, o.R, cos_begin, sin_begin, cos_end, sin_end);
    return segment;
  };
  // Where the part not yet handled begins.
  double at = part.begin_rad, cos_at = part.cos_begin, sin_at = part.sin_begin;
  // The arc over a part no segment covers: a new segment where it bounds the range.
  const auto fill = [&](double end, double cos_end, double sin_end) {
    if (!(end - at > kAzimuthSlack_rad)) return;
    const Segment segment = owned(part, at, cos_at, sin_at, end, cos_end, sin_end);
    if (std::isfinite(segment.farthest_m)) emit(segment);
  };
  for (int i = 0; i < current.count; ++i) {
    const Segment& x = current.segments[static_cast<std::size_t>(i)];
    if (at >= part.end_rad || x.end_rad <= at) {
      emit(x);
      continue;
    }
    if (x.begin_rad >= part.end_rad) {
      fill(part.end_rad, part.cos_end, part.sin_end);
      at = part.end_rad;
      emit(x);
      continue;
    }
    if (x.begin_rad > at) {
      fill(x.begin_rad, x.cos_begin, x.sin_begin);
      at = x.begin_rad, cos_at = x.cos_begin, sin_at = x.sin_begin;
    }
    // [at, v]: where the arc and segment x overlap. The arc takes it over when its farthest
    // range there is nearer than x's owner's; x's owner keeps the rest, bounded over it alone.
    const bool arc_ends_first = part.end_rad < x.end_rad;
    const double v = arc_ends_first ? part.end_rad : x.end_rad;
    const double cos_v = arc_ends_first ? part.cos_end : x.cos_end;
    const double sin_v = arc_ends_first ? part.sin_end : x.sin_end;
    const Segment taken = owned(part, at, cos_at, sin_at, v, cos_v, sin_v);
    const double kept_m = farthest_m(x.a, x.b, x.c, x.R, cos_at, sin_at, cos_v, sin_v);
    if (taken.farthest_m < kept_m) {
      emit(owned(x, x.begin_rad, x.cos_begin, x.sin_begin, at, cos_at, sin_at));
      emit(taken);
      emit(owned(x, v, cos_v, sin_v, x.end_rad, x.cos_end, x.sin_end));
    } else {
      emit(x);
    }
    at = v, cos_at = cos_v, sin_at = sin_v;
  }
  fill(part.end_rad, part.cos_end, part.sin_end);
  // Too many segments: neighbours that meet are joined, the pair whose farther bound is nearest
  // first, into one bounded by that constant (1/r = c, a circle); when none meet, the narrowest
  // is left out.
  while (count > kSegments) {
    int join = -1;
    double join_m = 0.0;
    for (int i = 0; i + 1 < count; ++i) {
      const Segment& l = next[static_cast<std::size_t>(i)];
      const Segment& r = next[static_cast<std::size_t>(i + 1)];
      if (r.begin_rad - l.end_rad > kAzimuthSlack_rad) continue;
      const double joined_m = std::max(l.farthest_m, r.farthest_m);
      if (join < 0 || joined_m < join_m) join = i, join_m = joined_m;
    }
    int removed = 0;
    if (join >= 0) {
      Segment& l = next[static_cast<std::size_t>(join)];
      const Segment& r = next[static_cast<std::size_t>(join + 1)];
      l.farthest_m = join_m;
      l.a = 0.0, l.b = 0.0, l.R = 0.0, l.c = 1.0 / join_m;
      l.end_rad = r.end_rad, l.cos_end = r.cos_end, l.sin_end = r.sin_end;
      removed = join + 1;
    } else {
      for (int i = 1; i < count; ++i) {
        const Segment& s = next[static_cast<std::size_t>(i)];
        const Segment& narrowest = next[static_cast<std::size_t>(removed)];
        if (s.end_rad - s.begin_rad < narrowest.end_rad - narrowest.begin_rad) removed = i;
      }
    }
    std::copy(next.begin() + removed + 1, next.begin() + count, next.begin() + removed);
    --count;
  }
  std::copy(next.begin(), next.begin() + count, current.segments.begin());
  current.count = count;
  // Covered once the segments join over the whole bin (gaps up to the slack count as met).
  double reached = bin * kBinWidth, farthest = 0.0;
  for (int i = 0; i < count; ++i) {
    const Segment& segment = current.segments[static_cast<std::size_t>(i)];
    if (segment.begin_rad > reached + kAzimuthSlack_rad) return;
    reached = std::max(reached, segment.end_rad);
    farthest = std::max(farthest, segment.farthest_m);
  }
  if (reached < (bin + 1) * kBinWidth - kAzimuthSlack_rad) return;
  // Every bound found so far holds (the envelope only comes nearer as arcs are added).
  bound = std::min(bound, farthest);
}

void OcclusionBins::cover(double begin_rad, double end_rad, double a, double b, double c) {
  if (!(end_rad > begin_rad)) return;
  const double R = std::sqrt(a * a + b * b);
  const double cos_begin = std::cos(begin_rad), sin_begin = std::sin(begin_rad);
  const double cos_end = std::cos(end_rad), sin_end = std::sin(end_rad);
  const int first = std::clamp(static_cast<int>(std::floor(begin_rad / kBinWidth)), 0, kBins - 1);
  const int last = std::clamp(static_cast<int>(std::floor(end_rad / kBinWidth)), 0, kBins - 1);
  for (int bin = first; bin <= last; ++bin) {
    const auto lo = static_cast<std::size_t>(bin);
    // The arc's part in the bin: its own ends where they lie inside, else the bin's edges.
    const bool own_begin = begin_rad > bin * kBinWidth;
    const bool own_end = end_rad < (bin + 1) * kBinWidth;
    Segment part{.begin_rad = own_begin ? begin_rad : bin * kBinWidth,
                 .end_rad = own_end ? end_rad : (bin + 1) * kBinWidth,
                 .cos_begin = own_begin ? cos_begin : cos_edge_[lo],
                 .sin_begin = own_begin ? sin_begin : sin_edge_[lo],
                 .cos_end = own_end ? cos_end : cos_edge_[lo + 1],
                 .sin_end = own_end ? sin_end : sin_edge_[lo + 1],
                 .a = a,
                 .b = b,
                 .c = c,
                 .R = R,
                 .farthest_m = 0.0};
    if (!(part.end_rad > part.begin_rad)) continue;
    part.farthest_m =
        farthest_m(a, b, c, R, part.cos_begin, part.sin_begin, part.cos_end, part.sin_end);
    // No positive range bound over the part (infinite): it covers nothing. Farther than the
    // bin's bound: it could still take over a piece of a segment, but seldom lowers the bound,
    // and testing costs more than the bins save (a bound left as it is holds).
    if (!(part.farthest_m < cover_m_[lo])) continue;
    cover_bin(bin, part);
  }
}

bool OcclusionBins::hides(const AzimuthSpan& span, double nearest_m) const {
  const double limit = nearest_m * (1.0 - kRangeSlack);
  if (!(limit > 0.0)) return false;
  if (span.whole) {
    return std::all_of(cover_m_.begin(), cover_m_.end(), [&](double m) { return m < limit; });
  }
  const int first = static_cast<int>(std::floor(span.begin_rad / kBinWidth));
  const int last = static_cast<int>(std::floor((span.begin_rad + span.width_rad) / kBinWidth));
  for (int j = first; j <= last; ++j) {
    if (!(cover_m_[static_cast<std::size_t>(j % kBins)] < limit)) return false;
  }
  return true;
}

}  // namespace conicloc::localizer
