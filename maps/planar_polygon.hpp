#pragma once
// A bounded planar landmark: a polygon (outer ring + holes) lying in a plane n·p + d = 0.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace conicloc::maps {

/// Plane n·p + d = 0 with |n| = 1 (DESIGN.md: "A plane is n·p + D = 0").
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;  ///< d, metres

  double signed_distance(const Eigen::Vector3d& point) const { return normal.dot(point) + offset; }
};

/// Orthonormal frame of a plane: p = origin + u·e_u + v·e_v, with e_u × e_v = n.
struct PlaneFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< foot point, on the plane
  Eigen::Vector3d e_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d e_v = Eigen::Vector3d::UnitY();

  Eigen::Vector2d project(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d q = p - origin;
    return {q.dot(e_u), q.dot(e_v)};
  }
  Eigen::Vector3d lift(const Eigen::Vector2d& uv) const {
    return origin + uv.x() * e_u + uv.y() * e_v;
  }
};

enum class SurfaceKind : std::uint8_t {
  Wall,     ///< |n_z| < sin(10°): vertical within 10°
  Floor,    ///< normal points up (into the free space above it)
  Ceiling,  ///< normal points down
  Slope,    ///< anything in between (ramps, sloped walls and roofs)
};

using Ring2 = std::vector<Eigen::Vector2d>;
using Ring3 = std::vector<Eigen::Vector3d>;

/// A polygon with holes on one plane. The 3D rings are the vertices projected onto the plane
/// (so they are exactly planar); the uv rings are the same vertices in `frame`. Rings are open
/// (last vertex != first), without repeated consecutive vertices, outer ring counter-clockwise
/// about `plane.normal`, holes clockwise. Build with make_planar_polygon() to keep all consistent.
struct PlanarPolygon {
  Plane plane;  ///< normal points into the free space the surface faces (the cell interior)
  PlaneFrame frame;
  Ring3 outer;
  std::vector<Ring3> holes;
  Ring2 outer_uv;
  std::vector<Ring2> holes_uv;
  Eigen::AlignedBox3d bounds;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  ///< area centroid of the outer ring
  double radius = 0.0;      ///< max distance of an outer vertex from `centroid` (bounding sphere)
  double area = 0.0;        ///< m², outer minus holes
  double flatness_m = 0.0;  ///< max distance of an input vertex from the fitted plane

  SurfaceKind kind = SurfaceKind::Wall;
  int cell = -1;          ///< index into PlaneMap::cells, -1 if none
  int storey = -1;        ///< index into PlaneMap::storeys, -1 if none
  std::string source_id;  ///< gml:id of the polygon (or of its cell) it came from
  /// True when the surface bounds free space on both sides (a thin wall between two cells, kept
  /// once after merging): plane.normal faces cell `cell`, the back faces `back_cell`.
  bool two_sided = false;
  int back_cell = -1;  ///< the cell behind a two-sided surface, -1 if none

  /// True when the uv point lies inside the outer ring and outside every hole (even-odd rule).
  bool contains_uv(const Eigen::Vector2d& uv) const;
};

/// Fits a plane to `outer` (Newell's method, then least squares through the centroid) and builds
/// a consistent PlanarPolygon. `outer` and `holes` may be closed or open and repeat vertices;
/// the orientation of `outer` defines the normal (right-hand rule). Returns false (and leaves
/// `out` unspecified) when the polygon is degenerate: fewer than 3 distinct vertices, or zero area.
bool make_planar_polygon(const Ring3& outer, const std::vector<Ring3>& holes, PlanarPolygon& out);

/// Even-odd point-in-ring test in 2D.
bool ring_contains(const Ring2& ring, const Eigen::Vector2d& point);

/// A ring seen from above: its points' x and y.
Ring2 plan_view(const Ring3& ring);

/// Signed area of a 2D ring (positive when counter-clockwise).
double signed_area(const Ring2& ring);

/// Classifies a unit normal of a surface facing into free space.
SurfaceKind classify_surface(const Eigen::Vector3d& normal);

}  // namespace conicloc::maps
