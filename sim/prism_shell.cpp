#include "sim/prism_shell.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>

namespace conicloc::sim {
namespace {

constexpr double kEps = 1e-9;
constexpr double kOnWall_m = 1e-6;  // a door this close to a wall line lies in it

Eigen::Vector3d at(const Eigen::Vector2d& xy, double z) {
  return {xy.x(), xy.y(), z};
}

struct Notch {
  double lo = 0.0;  // along the wall, m
  double hi = 0.0;
  double top_z = 0.0;
};

// The outer ring of the wall of `cell` on footprint edge p -> q. In wall coordinates (s along
// p -> q, z up) it runs counter-clockwise: along the floor (down and up every door notch), up,
// back along the ceiling. e_s × e_z is the outward normal of a counter-clockwise footprint edge,
// so the ring faces out of the cell.
maps::Ring3 wall_ring(const PrismCell& cell, const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                      const std::vector<DoorOpening>& doors) {
  const double length = (q - p).norm();
  const Eigen::Vector2d along = (q - p) / length;
  auto xy = [&](double s) -> Eigen::Vector2d { return p + s * along; };
  auto floor_at = [&](double s) { return cell.floor_at(xy(s).x()); };

  std::vector<double> stops = {0.0, length};
  if (!cell.floor_profile.empty() && std::abs(along.x()) > kEps) {  // the stair's breaks
    for (const auto& point : cell.floor_profile) {
      const double s = (point.x() - p.x()) / along.x();
      if (s > kEps && s < length - kEps) stops.push_back(s);
    }
  }
  std::vector<Notch> notches;
  for (const auto& door : doors) {
    if (door.cells[0] != cell.id && door.cells[1] != cell.id) continue;
    const Eigen::Vector2d a = door.p0 - p;
    const Eigen::Vector2d b = door.p1 - p;
    const double off_a = std::abs(a.x() * along.y() - a.y() * along.x());
    const double off_b = std::abs(b.x() * along.y() - b.y() * along.x());
    const double lo = std::min(a.dot(along), b.dot(along));
    const double hi = std::max(a.dot(along), b.dot(along));
    if (off_a > kOnWall_m || off_b > kOnWall_m || lo < -kOnWall_m || hi > length + kOnWall_m) {
      continue;
    }
    assert(std::abs(door.z0 - floor_at(lo)) < 1e-6 && std::abs(door.z0 - floor_at(hi)) < 1e-6);
    notches.push_back({lo, hi, door.z1});
    stops.push_back(lo);
    stops.push_back(hi);
  }
  std::sort(stops.begin(), stops.end());
  stops.erase(std::unique(stops.begin(), stops.end(),
                          [](double u, double v) { return std::abs(u - v) < kEps; }),
              stops.end());

  maps::Ring3 ring;
  for (const double s : stops) {
    const bool inside_notch = std::any_of(notches.begin(), notches.end(), [&](const Notch& n) {
      return n.lo + kEps < s && s < n.hi - kEps;
    });
    if (inside_notch) continue;
    for (const auto& n : notches) {  // leaving a notch: down its right jamb
      if (std::abs(n.hi - s) < kEps) ring.push_back(at(xy(s), n.top_z));
    }
    ring.push_back(at(xy(s), floor_at(s)));
    for (const auto& n : notches) {  // entering a notch: up its left jamb
      if (std::abs(n.lo - s) < kEps) ring.push_back(at(xy(s), n.top_z));
    }
  }
  ring.push_back(at(q, cell.ceiling_at(q.x(), q.y())));
  ring.push_back(at(p, cell.ceiling_at(p.x(), p.y())));
  return ring;
}

maps::Ring3 lifted(const maps::Ring2& ring, double z, bool reversed) {
  maps::Ring3 out;
  for (const auto& p : ring) out.push_back(at(p, z));
  if (reversed) std::reverse(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<ShellPolygon> exterior_shell(const PrismCell& cell,
                                         const std::vector<DoorOpening>& doors) {
  std::vector<ShellPolygon> shell;
  const maps::Ring2& fp = cell.footprint;
  if (!cell.floor_profile.empty()) {
    // Sloped floor segments across the (rectangular) footprint, facing down.
    double y_lo = fp.front().y();
    double y_hi = y_lo;
    for (const auto& p : fp) y_lo = std::min(y_lo, p.y()), y_hi = std::max(y_hi, p.y());
    const auto& profile = cell.floor_profile;
    for (std::size_t i = 1; i < profile.size(); ++i) {
      const Eigen::Vector2d& a = profile[i - 1];
      const Eigen::Vector2d& b = profile[i];
      shell.push_back(
          {"floor-" + std::to_string(i - 1),
           {{a.x(), y_hi, a.y()}, {b.x(), y_hi, b.y()}, {b.x(), y_lo, b.y()}, {a.x(), y_lo, a.y()}},
           {}});
    }
  } else {
    ShellPolygon floor{"floor", lifted(fp, cell.floor_z, true), {}};
    for (const auto& pillar : cell.pillars)
      floor.holes.push_back(lifted(pillar, cell.floor_z, false));
    shell.push_back(std::move(floor));
  }
  ShellPolygon ceiling{"ceiling", {}, {}};
  for (const auto& p : fp) ceiling.outer.push_back(at(p, cell.ceiling_at(p.x(), p.y())));
  for (const auto& pillar : cell.pillars)
    ceiling.holes.push_back(lifted(pillar, cell.ceiling.x(), true));
  shell.push_back(std::move(ceiling));
  for (std::size_t i = 0; i < fp.size(); ++i) {
    shell.push_back(
        {"wall-" + std::to_string(i), wall_ring(cell, fp[i], fp[(i + 1) % fp.size()], doors), {}});
  }
  return shell;
}

std::vector<std::vector<ShellPolygon>> pillar_shells(const PrismCell& cell) {
  std::vector<std::vector<ShellPolygon>> shells;
  const double bottom = cell.floor_z;
  const double top = cell.ceiling.x();
  for (std::size_t k = 0; k < cell.pillars.size(); ++k) {
    const maps::Ring2& ring = cell.pillars[k];
    const std::string tag = "pillar" + std::to_string(k) + "-";
    std::vector<ShellPolygon> shell;
    shell.push_back({tag + "bottom", lifted(ring, bottom, false), {}});  // faces up, into it
    shell.push_back({tag + "top", lifted(ring, top, true), {}});         // faces down, into it
    for (std::size_t i = 0; i < ring.size(); ++i) {
      // a -> a' -> b' -> b: the normal is z × (b - a), left of the counter-clockwise edge: inward.
      const Eigen::Vector2d& a = ring[i];
      const Eigen::Vector2d& b = ring[(i + 1) % ring.size()];
      shell.push_back({tag + "side-" + std::to_string(i),
                       {at(a, bottom), at(a, top), at(b, top), at(b, bottom)},
                       {}});
    }
    shells.push_back(std::move(shell));
  }
  return shells;
}

maps::Ring3 door_ring(const DoorOpening& door, const PrismCell& first) {
  maps::Ring3 ring = {at(door.p0, door.z0), at(door.p1, door.z0), at(door.p1, door.z1),
                      at(door.p0, door.z1)};
  // The ring's right-hand normal is right of p0 -> p1; it must point away from the first cell.
  const Eigen::Vector2d d = door.p1 - door.p0;
  const Eigen::Vector2d right(d.y(), -d.x());
  if (right.dot(0.5 * (door.p0 + door.p1) - first.centroid()) < 0.0) {
    ring = {ring[1], ring[0], ring[3], ring[2]};
  }
  return ring;
}

}  // namespace conicloc::sim
