#include "localizer/conic/polygon_arcs.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace conicloc::localizer {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Relative tolerance of the wedge test: crossings this close outside an edge's end still count.
constexpr double kWedgeTolerance = 1e-9;

double wrap(double theta) {
  theta = std::fmod(theta, kTwoPi);
  return theta < 0.0 ? theta + kTwoPi : theta;
}

// Crossings closer than this (radians) or tangent ones make the parity walk unsafe.
constexpr double kParityMinGap_rad = 1e-8;

// Appends the azimuths where the beam of `ring` crosses the edge p0→p1 (sensor frame) of vertex
// ring `vertex_ring` inside the segment. Returns false when the beam only touches the edge's
// line (a double root: a tangent, not a crossing).
bool edge_crossings(const RingGeometry& ring, const double* p0_in, const double* p1_in,
                    int vertex_ring, std::vector<PredictionWorkspace::EdgeCrossing>& crossings) {
  const double o = ring.vertical_offset_m;
  const Eigen::Vector3d p0(p0_in[0], p0_in[1], p0_in[2] - o);
  const Eigen::Vector3d p1(p1_in[0], p1_in[1], p1_in[2] - o);
  const Eigen::Vector3d m = p0.cross(p1);
  const double alpha = m.x() * ring.cos_elevation;
  const double beta = m.y() * ring.cos_elevation;
  const double gamma = -m.z() * ring.sin_elevation;
  const double radius_sq = alpha * alpha + beta * beta;
  // R = 0: the edge's apex plane is level; a ring with φ ≠ 0 never lies in it (φ = 0: always,
  // then the hit point never crosses the edge line transversally). No crossing either way.
  if (!(radius_sq > 0.0) || gamma * gamma > radius_sq * (1.0 + 1e-12)) return true;
  // Unit solutions without trigonometry: (cos θ, sin θ) = (α c' ∓ β s, β c' ± α s)/R with
  // c' = γ/R, s = √(1 − c'²); one atan2 only for a crossing that lies on the segment.
  const double inv_radius = 1.0 / std::sqrt(radius_sq);
  const double along = std::clamp(gamma * inv_radius, -1.0, 1.0);
  const double across = std::sqrt(std::max(0.0, 1.0 - along * along));
  const double ua = alpha * inv_radius, ub = beta * inv_radius;
  // Wedge tolerance τ = ε |m| max(|p0|, |p1|), compared squared (no square roots): a dot
  // product t passes when t ≥ 0 or t² ≤ τ².
  const double tolerance_sq = kWedgeTolerance * kWedgeTolerance * m.squaredNorm() *
                              std::max(p0.squaredNorm(), p1.squaredNorm());
  auto within = [tolerance_sq](double t) { return t >= 0.0 || t * t <= tolerance_sq; };
  bool transversal = true;
  for (const double sign : {-1.0, 1.0}) {
    const double cos_t = ua * along - sign * ub * across;
    const double sin_t = ub * along + sign * ua * across;
    const Eigen::Vector3d d(ring.cos_elevation * cos_t, ring.cos_elevation * sin_t,
                            ring.sin_elevation);
    // d in the forward wedge of p0 and p1: d = λ p0 + μ p1 with λ, μ ≥ 0.
    const double at_p0 = p0.cross(d).dot(m), at_p1 = d.cross(p1).dot(m);
    if (within(at_p0) && within(at_p1)) {
      crossings.push_back({wrap(std::atan2(sin_t, cos_t)), vertex_ring});
      // The two roots are 2·asin(across) apart: closer than the gap, a (near) tangent. A
      // crossing within the tolerance of a vertex may be one the neighbouring edge reports too,
      // or one just past the edge's end: it splits an interval harmlessly but must not flip a
      // state, so the parity walk is not used.
      transversal = transversal && across > 0.5 * kParityMinGap_rad &&
                    at_p0 * at_p0 > tolerance_sq && at_p1 * at_p1 > tolerance_sq;
    }
    if (across == 0.0) break;
  }
  return transversal;
}

// Where the beam of `ring` at azimuth θ hits the plane of `conic` at a positive range, that point
// in the polygon's plane frame (u, v); false when the beam does not reach the plane.
bool hit_uv(const RingGeometry& ring, const PredictionWorkspace::SensorPolygon& polygon,
            const RingConic& conic, double theta, Eigen::Vector2d& uv) {
  const double cos_t = std::cos(theta), sin_t = std::sin(theta);
  const double den = conic.denominator(cos_t, sin_t);
  if (!((conic.E > 0.0 && den > 0.0) || (conic.E < 0.0 && den < 0.0))) return false;
  const double r = conic.E / den;
  const double x = r * ring.cos_elevation * cos_t - polygon.origin[0];
  const double y = r * ring.cos_elevation * sin_t - polygon.origin[1];
  const double z = ring.vertical_offset_m + r * ring.sin_elevation - polygon.origin[2];
  uv = {x * polygon.e_u[0] + y * polygon.e_u[1] + z * polygon.e_u[2],
        x * polygon.e_v[0] + y * polygon.e_v[1] + z * polygon.e_v[2]};
  return true;
}

bool inside_polygon(const RingGeometry& ring, const PredictionWorkspace::SensorPolygon& polygon,
                    const maps::PlanarPolygon& map_polygon, const RingConic& conic, double theta) {
  Eigen::Vector2d uv;
  return hit_uv(ring, polygon, conic, theta, uv) && map_polygon.contains_uv(uv);
}

// The parity walk is exact when every crossing is transversal, apart from the neighbouring
// crossings of its own vertex ring (around the circle), and each vertex ring is crossed an even
// number of times. Crossings of different rings may coincide (a door hole sharing the wall's
// bottom edge): each ring's state still flips at its own crossings.
bool parity_is_safe(const std::vector<PredictionWorkspace::EdgeCrossing>& sorted,
                    std::vector<char>& odd_count, std::vector<double>& first_crossing,
                    std::vector<double>& last_crossing) {
  std::fill(odd_count.begin(), odd_count.end(), 0);
  constexpr double kNone = -1.0;  // azimuths are ≥ 0 (or −0)
  first_crossing.assign(odd_count.size(), kNone);
  last_crossing.assign(odd_count.size(), kNone);
  for (const auto& crossing : sorted) {
    const auto r = static_cast<std::size_t>(crossing.ring);
    if (last_crossing[r] != kNone &&
        !(crossing.azimuth_rad - last_crossing[r] > kParityMinGap_rad)) {
      return false;
    }
    if (first_crossing[r] == kNone) first_crossing[r] = crossing.azimuth_rad;
    last_crossing[r] = crossing.azimuth_rad;
    odd_count[r] ^= 1;
  }
  for (std::size_t r = 0; r < odd_count.size(); ++r) {
    if (odd_count[r] != 0) return false;
    if (first_crossing[r] != kNone && first_crossing[r] != last_crossing[r] &&
        !(first_crossing[r] + kTwoPi - last_crossing[r] > kParityMinGap_rad)) {
      return false;
    }
  }
  return true;
}

// Appends [t0, t1] to the polygon's arcs, merged with the previous one when contiguous.
void append_arc(std::vector<PredictionWorkspace::Arc>& arcs, std::size_t first_new, double t0,
                double t1, double a, double b, double c, int polygon) {
  if (arcs.size() > first_new && arcs.back().end_rad == t0) {
    arcs.back().end_rad = t1;
  } else {
    arcs.push_back({t0, t1, a, b, c, polygon});
  }
}

}  // namespace

void add_sensor_polygon(const maps::PlanarPolygon& polygon, int index, const Pose3& T_map_sensor,
                        PredictionWorkspace& workspace) {
  const Eigen::Matrix3d R_t = T_map_sensor.linear().transpose();
  const Eigen::Vector3d t = T_map_sensor.translation();
  PredictionWorkspace::SensorPolygon out;
  out.polygon = index;
  const Eigen::Vector3d n = R_t * polygon.plane.normal;
  out.offset = polygon.plane.offset + polygon.plane.normal.dot(t);  // D_s = D + n·t
  const Eigen::Vector3d origin = R_t * (polygon.frame.origin - t);
  const Eigen::Vector3d e_u = R_t * polygon.frame.e_u;
  const Eigen::Vector3d e_v = R_t * polygon.frame.e_v;
  const Eigen::Vector3d centre = R_t * (polygon.centroid - t);
  for (int i = 0; i < 3; ++i) {
    out.normal[i] = n[i];
    out.origin[i] = origin[i];
    out.e_u[i] = e_u[i];
    out.e_v[i] = e_v[i];
    out.centre[i] = centre[i];
  }
  out.radius = polygon.radius;
  out.ring_entry_begin = workspace.ring_begin.size();
  auto add_ring = [&](const maps::Ring3& ring3) {
    workspace.ring_begin.push_back(workspace.vertex_x.size());
    for (const auto& p : ring3) {
      const Eigen::Vector3d q = R_t * (p - t);
      workspace.vertex_x.push_back(q.x());
      workspace.vertex_y.push_back(q.y());
      workspace.vertex_z.push_back(q.z());
    }
  };
  add_ring(polygon.outer);
  for (const auto& hole : polygon.holes) add_ring(hole);
  out.ring_entry_end =
      workspace.ring_begin.size();  // ring_begin entries [ring_entry_begin, ring_entry_end)
  workspace.ring_begin.push_back(workspace.vertex_x.size());  // end marker of the last ring
  workspace.polygons.push_back(out);
}

ArcClassification append_polygon_arcs(const RingGeometry& ring,
                                      const PredictionWorkspace::SensorPolygon& polygon,
                                      const maps::PlanarPolygon& map_polygon,
                                      PredictionWorkspace& workspace,
                                      std::vector<PredictionWorkspace::Arc>& arcs,
                                      ArcClassification classification) {
  const RingConic conic = ring_conic(ring, sensor_plane(polygon));
  if (conic.E == 0.0) return classification;  // apex on the plane: no positive range
  // Some beam reaches the plane iff R cos(θ − ψ) > −sC has a solution (visible_interval), i.e.
  // R > −sC. No split points at the interval's ends are needed: next to an asymptote the hit
  // point runs to infinity, outside the bounded polygon, and inside/outside only changes at edge
  // crossings — so an interval holding an asymptote is outside on both sides, and its midpoint
  // (a miss, or a far hit) classifies it correctly.
  const double s = conic.E > 0.0 ? 1.0 : -1.0;
  if (!(std::sqrt(conic.A * conic.A + conic.B * conic.B) > -s * conic.C)) return classification;

  auto& crossings = workspace.edge_crossings;
  crossings.clear();
  bool transversal = true;
  // Each vertex ring of the polygon: its ring_begin entry and the next one (the end marker
  // follows the polygon's last ring) bound its vertices.
  for (std::size_t r = polygon.ring_entry_begin; r < polygon.ring_entry_end; ++r) {
    const std::size_t first = workspace.ring_begin[r];
    const std::size_t end = workspace.ring_begin[r + 1];
    const int vertex_ring = static_cast<int>(r - polygon.ring_entry_begin);
    for (std::size_t i = first; i < end; ++i) {
      const std::size_t j = i + 1 < end ? i + 1 : first;
      const double p0[3] = {workspace.vertex_x[i], workspace.vertex_y[i], workspace.vertex_z[i]};
      const double p1[3] = {workspace.vertex_x[j], workspace.vertex_y[j], workspace.vertex_z[j]};
      transversal = edge_crossings(ring, p0, p1, vertex_ring, crossings) && transversal;
    }
  }
  std::sort(crossings.begin(), crossings.end(),
            [](const auto& l, const auto& r) { return l.azimuth_rad < r.azimuth_rad; });
  const double a = conic.A / conic.E, b = conic.B / conic.E, c = conic.C / conic.E;
  const std::size_t first_new = arcs.size();
  const std::size_t vertex_rings = polygon.ring_entry_end - polygon.ring_entry_begin;
  std::vector<char>& inside_ring = workspace.inside_ring;
  inside_ring.resize(vertex_rings);
  const bool parity =
      classification == ArcClassification::kCrossingParity && transversal &&
      parity_is_safe(crossings, inside_ring, workspace.first_crossing, workspace.last_crossing);
  // Intervals between consecutive boundaries 0, crossings…, 2π.
  const std::size_t intervals = crossings.size() + 1;
  auto boundary = [&](std::size_t i) {
    return i == 0 ? 0.0 : i == intervals ? kTwoPi : crossings[i - 1].azimuth_rad;
  };
  if (!parity) {
    for (std::size_t i = 0; i < intervals; ++i) {
      const double t0 = boundary(i), t1 = boundary(i + 1);
      if (!(t1 > t0)) continue;
      if (!inside_polygon(ring, polygon, map_polygon, conic, 0.5 * (t0 + t1))) continue;
      append_arc(arcs, first_new, t0, t1, a, b, c, polygon.polygon);
    }
    return ArcClassification::kMidpointTests;
  }
  // One even-odd test per vertex ring at the middle of the widest interval (≥ 2π/intervals, so
  // its midpoint is far from every edge crossing, where the test would be ambiguous); no hit
  // there: outside all, as next to the visible interval's ends, where the hit point runs to
  // infinity. Undoing the toggles of the crossings before it gives the states at θ = 0.
  std::size_t widest = 0;
  for (std::size_t i = 1; i < intervals; ++i) {
    if (boundary(i + 1) - boundary(i) > boundary(widest + 1) - boundary(widest)) widest = i;
  }
  Eigen::Vector2d uv;
  const bool hits =
      hit_uv(ring, polygon, conic, 0.5 * (boundary(widest) + boundary(widest + 1)), uv);
  for (std::size_t r = 0; r < vertex_rings; ++r) {
    const maps::Ring2& ring_uv = r == 0 ? map_polygon.outer_uv : map_polygon.holes_uv[r - 1];
    inside_ring[r] = hits && maps::ring_contains(ring_uv, uv);
  }
  for (std::size_t i = 0; i < widest; ++i) {
    const auto r = static_cast<std::size_t>(crossings[i].ring);
    inside_ring[r] = !inside_ring[r];
  }
  int holes_inside = 0;
  for (std::size_t r = 1; r < vertex_rings; ++r) holes_inside += inside_ring[r] ? 1 : 0;
  for (std::size_t i = 0; i < intervals; ++i) {
    const double t0 = boundary(i), t1 = boundary(i + 1);
    if (t1 > t0 && inside_ring[0] && holes_inside == 0) {
      append_arc(arcs, first_new, t0, t1, a, b, c, polygon.polygon);
    }
    if (i + 1 == intervals) break;
    const auto r = static_cast<std::size_t>(crossings[i].ring);
    inside_ring[r] = !inside_ring[r];
    if (r > 0) holes_inside += inside_ring[r] ? 1 : -1;
  }
  return ArcClassification::kCrossingParity;
}

}  // namespace conicloc::localizer
