// PlaneMap -> Wavefront OBJ (+ MTL): triangulated polygons grouped by cell and surface kind.
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <ostream>

#include "io/input_error.hpp"
#include "io/map_export.hpp"
#include "maps/polygon_triangulation.hpp"

namespace conicloc::io {
namespace {

constexpr int kNoCell = std::numeric_limits<int>::max();  // sorts polygons without a cell last

const char* kind_name(maps::SurfaceKind kind) {
  switch (kind) {
    case maps::SurfaceKind::Wall:
      return "wall";
    case maps::SurfaceKind::Floor:
      return "floor";
    case maps::SurfaceKind::Ceiling:
      return "ceiling";
    case maps::SurfaceKind::Slope:
      return "slope";
  }
  return "wall";
}

// OBJ names end at whitespace: keep ids readable but on one token.
std::string obj_name(std::string name) {
  if (name.empty()) return "unnamed";
  std::replace_if(
      name.begin(), name.end(), [](unsigned char c) { return std::isspace(c); }, '_');
  return name;
}

}  // namespace

ObjStats write_obj(const maps::PlaneMap& map, std::ostream& out, const std::string& mtl_file) {
  ObjStats stats;
  out << "# conicloc PlaneMap: " << map.polygons.size() << " polygons, " << map.cells.size()
      << " cells; map frame, metres (file coordinates = these + origin)\n";
  out << std::setprecision(17) << "# origin " << map.origin.x() << ' ' << map.origin.y() << ' '
      << map.origin.z() << '\n';
  if (!mtl_file.empty()) out << "mtllib " << mtl_file << '\n';
  out << std::fixed << std::setprecision(6);

  // Polygons ordered by cell (those without one last), then by kind, so each `o`/`g` is one block.
  std::vector<std::size_t> order(map.polygons.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto cell_key = [&](std::size_t i) {
    const int cell = map.polygons[i].cell;
    return cell >= 0 && cell < static_cast<int>(map.cells.size()) ? cell : kNoCell;
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::pair(cell_key(a), map.polygons[a].kind) <
           std::pair(cell_key(b), map.polygons[b].kind);
  });

  int current_cell = -2;
  int current_kind = -1;
  for (const std::size_t i : order) {
    const maps::PlanarPolygon& polygon = map.polygons[i];
    const int cell = cell_key(i);
    if (cell != current_cell) {
      current_cell = cell;
      current_kind = -1;
      const bool has_cell = cell != kNoCell;
      out << "o "
          << (has_cell ? obj_name(map.cells[static_cast<std::size_t>(cell)].id)
                       : std::string("unassigned"))
          << '\n';
      ++stats.objects;
    }
    if (static_cast<int>(polygon.kind) != current_kind) {
      current_kind = static_cast<int>(polygon.kind);
      const std::string cell_name =
          cell != kNoCell ? obj_name(map.cells[static_cast<std::size_t>(cell)].id) : "unassigned";
      out << "g " << cell_name << '/' << kind_name(polygon.kind) << '\n';
      out << "usemtl " << kind_name(polygon.kind) << '\n';
      ++stats.groups;
    }

    const auto triangles = maps::triangulate(polygon);
    if (triangles.empty()) continue;
    const int first = stats.vertices + 1;  // OBJ indices are 1-based and global
    auto write_ring = [&](const maps::Ring3& ring) {
      for (const auto& p : ring) out << "v " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
      stats.vertices += static_cast<int>(ring.size());
    };
    write_ring(polygon.outer);
    for (const auto& hole : polygon.holes) write_ring(hole);
    const auto& n = polygon.plane.normal;
    out << "vn " << n.x() << ' ' << n.y() << ' ' << n.z() << '\n';
    const int normal_index = ++stats.normals;
    for (const auto& t : triangles) {
      out << "f " << first + t[0] << "//" << normal_index << ' ' << first + t[1] << "//"
          << normal_index << ' ' << first + t[2] << "//" << normal_index << '\n';
      ++stats.faces;
    }
  }
  return stats;
}

ObjStats write_obj_file(const maps::PlaneMap& map, const std::string& path) {
  const std::filesystem::path obj_path(path);
  std::filesystem::path mtl_path = obj_path;
  mtl_path.replace_extension(".mtl");
  {
    std::ofstream mtl(mtl_path);
    if (!mtl) throw InputError(mtl_path.string(), "", "cannot write the material file");
    // Diffuse colours per surface kind, as in the SVG floor plan.
    mtl << "# conicloc surface kinds\n"
        << "newmtl wall\nKd 0.80 0.78 0.74\n\n"
        << "newmtl floor\nKd 0.62 0.55 0.45\n\n"
        << "newmtl ceiling\nKd 0.90 0.90 0.92\n\n"
        << "newmtl slope\nKd 0.70 0.55 0.35\n";
    if (!mtl) throw InputError(mtl_path.string(), "", "write failed");
  }
  std::ofstream out(obj_path);
  if (!out) throw InputError(path, "", "cannot write the OBJ file");
  const ObjStats stats = write_obj(map, out, mtl_path.filename().string());
  out.flush();
  if (!out) throw InputError(path, "", "write failed");
  return stats;
}

}  // namespace conicloc::io
