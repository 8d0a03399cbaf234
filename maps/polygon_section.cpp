#include "maps/polygon_section.hpp"

#include <algorithm>
#include <cmath>

namespace conicloc::maps {
namespace {

// In the polygon's uv frame the section is the line g(uv) = a·u + b·v - c = 0 with
// (a, b) = (e_u.z, e_v.z) and c = height - origin.z; points on it are parametrised by
// t = uv · (-b, a) / |(a, b)|.
struct SectionLine {
  Eigen::Vector2d gradient;  // (a, b)
  double c = 0.0;
  Eigen::Vector2d direction;  // unit, along the line

  double value(const Eigen::Vector2d& uv) const { return gradient.dot(uv) - c; }
};

bool section_line(const PlanarPolygon& polygon, double height_m, SectionLine& line) {
  line.gradient = Eigen::Vector2d(polygon.frame.e_u.z(), polygon.frame.e_v.z());
  const double slope = line.gradient.norm();  // = sin(tilt from horizontal)
  if (slope < 1e-3) return false;
  line.c = height_m - polygon.frame.origin.z();
  line.direction = Eigen::Vector2d(-line.gradient.y(), line.gradient.x()) / slope;
  return true;
}

// Line parameters where the ring's edges cross the line (half-open rule: a vertex on the line
// counts once for the edge leaving it upward).
void add_crossings(const Ring2& ring, const SectionLine& line, std::vector<double>& ts) {
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector2d& p = ring[i];
    const Eigen::Vector2d& q = ring[(i + 1) % ring.size()];
    const double gp = line.value(p);
    const double gq = line.value(q);
    if ((gp < 0.0) == (gq < 0.0)) continue;
    const Eigen::Vector2d crossing = p + (gp / (gp - gq)) * (q - p);
    ts.push_back(crossing.dot(line.direction));
  }
}

std::vector<SectionSegment> pair_up(const PlanarPolygon& polygon, const SectionLine& line,
                                    std::vector<double> ts) {
  std::sort(ts.begin(), ts.end());
  // The foot of the line in uv: the point of the line nearest the frame origin.
  const Eigen::Vector2d foot = line.gradient * (line.c / line.gradient.squaredNorm());
  std::vector<SectionSegment> segments;
  for (std::size_t i = 0; i + 1 < ts.size(); i += 2) {
    if (ts[i + 1] - ts[i] <= 0.0) continue;
    segments.push_back({polygon.frame.lift(foot + ts[i] * line.direction),
                        polygon.frame.lift(foot + ts[i + 1] * line.direction)});
  }
  return segments;
}

}  // namespace

std::vector<SectionSegment> horizontal_section(const PlanarPolygon& polygon, double height_m) {
  SectionLine line;
  if (!section_line(polygon, height_m, line)) return {};
  std::vector<double> ts;
  add_crossings(polygon.outer_uv, line, ts);
  for (const auto& hole : polygon.holes_uv) add_crossings(hole, line, ts);
  return pair_up(polygon, line, std::move(ts));
}

std::vector<SectionSegment> horizontal_section_of_holes(const PlanarPolygon& polygon,
                                                        double height_m) {
  SectionLine line;
  if (!section_line(polygon, height_m, line)) return {};
  std::vector<SectionSegment> segments;
  for (const auto& hole : polygon.holes_uv) {
    std::vector<double> ts;
    add_crossings(hole, line, ts);
    auto pieces = pair_up(polygon, line, std::move(ts));
    segments.insert(segments.end(), pieces.begin(), pieces.end());
  }
  return segments;
}

}  // namespace conicloc::maps
