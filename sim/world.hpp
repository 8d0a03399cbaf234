#pragma once
// The world the simulated sensor sees: the (perturbed) map surfaces, clutter boxes the map lacks,
// and people walking about. Holes in polygons (doors, windows, glass) return nothing.

#include <Eigen/Geometry>
#include <optional>
#include <span>
#include <vector>

#include "maps/planar_polygon.hpp"
#include "sim/moving_person.hpp"
#include "sim/people_grid.hpp"
#include "sim/polygon_bvh.hpp"

namespace conicloc::sim {

enum class SurfaceOrigin : std::uint8_t { Map, Furniture, Person };

struct SurfaceMaterial {
  double reflectivity = 50.0;  ///< Velodyne calibrated reflectivity of a diffuse surface, 0..100
  SurfaceOrigin origin = SurfaceOrigin::Map;
};

struct WorldHit {
  double range_m = 0.0;
  double cos_incidence = 1.0;  ///< |n·d|, for the echo strength
  SurfaceMaterial material;
  int polygon = -1;  ///< polygon index in the world, −1 for a person
};

/// Some of the people and where they stand at one instant.
struct PeopleSnapshot {
  std::vector<std::size_t> index;       ///< into World::people()
  std::vector<Eigen::Vector2d> centre;  ///< of each, map frame
};

class World {
 public:
  World() = default;
  /// `materials[i]` describes `polygons[i]`.
  World(std::vector<maps::PlanarPolygon> polygons, std::vector<SurfaceMaterial> materials,
        std::vector<MovingPerson> people);

  /// The people at `time_s` that rays[k] may meet before reach_m[k] (their surfaces): the others
  /// stand above or below every ray's span, z ∈ o_z + t·d_z for t ∈ [0, reach] (on other
  /// storeys, behind the slabs the rays stop at), or farther from every origin than the farthest
  /// reach. Only the people whose walks come within reach are visited (a grid of the walks,
  /// PeopleGrid), and only those the heights leave in have their positions computed. The 16 rays
  /// of a firing sequence span 35 µs, in which a walking person moves < 0.1 mm: they share one
  /// instant.
  PeopleSnapshot people_in_reach(double time_s, std::span<const Ray> rays,
                                 std::span<const double> reach_m) const;

  /// Nearest map surface (polygon) along `ray` in (min_range_m, max_range_m), people ignored.
  std::optional<WorldHit> nearest_surface(const Ray& ray, double min_range_m, double max_range_m,
                                          int hint = -1) const;

  /// nearest_surface() of each ray of a fan from about one point (a firing), rays[k] with hint
  /// hints[k], into out[k]: the fan shares its descent of the polygon tree (PolygonBvh). A hint
  /// is a polygon to try first; it does not change the result.
  void nearest_surfaces(std::span<const Ray> rays, double min_range_m, double max_range_m,
                        std::span<const int> hints, std::span<std::optional<WorldHit>> out) const;

  /// `surface` (nearest_surface()'s answer), or the person of `people` that stands nearer along
  /// `ray` within (min_range_m, max_range_m).
  std::optional<WorldHit> nearer_person(const Ray& ray, const PeopleSnapshot& people,
                                        double min_range_m, double max_range_m,
                                        std::optional<WorldHit> surface) const;

  const std::vector<maps::PlanarPolygon>& polygons() const { return bvh_.polygons(); }
  const std::vector<SurfaceMaterial>& materials() const { return materials_; }
  const std::vector<MovingPerson>& people() const { return people_; }

 private:
  WorldHit world_hit(const Ray& ray, const PolygonHit& hit) const;

  PolygonBvh bvh_;
  std::vector<SurfaceMaterial> materials_;
  std::vector<MovingPerson> people_;
  /// people_[i]'s centre stays in paths_[i], the box of its walk from → to.
  std::vector<Eigen::AlignedBox2d> paths_;
  PeopleGrid people_grid_;  ///< over the paths widened by each person's radius
};

}  // namespace conicloc::sim
