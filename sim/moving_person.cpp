#include "sim/moving_person.hpp"

#include <cmath>

namespace conicloc::sim {

Eigen::Vector2d MovingPerson::position(double time_s) const {
  const double length = (to - from).norm();
  if (length < 1e-9 || speed_mps <= 0.0) return from;
  const double period = 2.0 * length / speed_mps;
  double phase = std::fmod(time_s + phase_s, period);
  if (phase < 0.0) phase += period;
  const double s = phase * speed_mps;  // distance walked in this period
  const double along = s <= length ? s : 2.0 * length - s;
  return from + (to - from) * (along / length);
}

std::optional<double> intersect_person(const MovingPerson& person, double time_s, const Ray& ray,
                                       double min_range_m, double max_range_m) {
  return intersect_person_at(person, person.position(time_s), ray, min_range_m, max_range_m);
}

std::optional<double> intersect_person_at(const MovingPerson& person,
                                          const Eigen::Vector2d& centre, const Ray& ray,
                                          double min_range_m, double max_range_m) {
  const Eigen::Vector2d o = ray.origin.head<2>() - centre;
  const Eigen::Vector2d d = ray.direction.head<2>();
  const double top_z = person.floor_z + person.height_m;
  std::optional<double> best;
  const double a = d.squaredNorm();
  if (a > 1e-18) {
    const double b = o.dot(d);
    const double c = o.squaredNorm() - person.radius_m * person.radius_m;
    const double discriminant = b * b - a * c;
    if (discriminant >= 0.0) {
      const double root = std::sqrt(discriminant);
      for (const double t : {(-b - root) / a, (-b + root) / a}) {
        if (!(t > min_range_m && t < max_range_m)) continue;
        const double z = ray.origin.z() + t * ray.direction.z();
        if (z >= person.floor_z && z <= top_z) {
          best = t;
          break;  // roots ascend: the first valid one is the nearest
        }
      }
    }
  }
  // The head (top disc), seen from above.
  if (std::abs(ray.direction.z()) > 1e-12) {
    const double t = (top_z - ray.origin.z()) / ray.direction.z();
    if (t > min_range_m && t < (best ? *best : max_range_m)) {
      const Eigen::Vector2d p = o + t * d;
      if (p.squaredNorm() <= person.radius_m * person.radius_m) best = t;
    }
  }
  return best;
}

}  // namespace conicloc::sim
