// PlaneMap -> SVG floor plan: per storey a horizontal section at a fixed height above the floor.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "io/input_error.hpp"
#include "io/map_export.hpp"
#include "io/xml_escape.hpp"
#include "maps/polygon_section.hpp"

namespace conicloc::io {
namespace {

// Colours: light fills per space class, dark walls, blue glazing, orange doors, green graph.
constexpr const char* kRoomFill = "#f6eedc";
constexpr const char* kCorridorFill = "#e3e9f1";
constexpr const char* kStairFill = "#cfe5f4";
constexpr const char* kConnectionFill = "#eee3f3";
constexpr const char* kNonNavigableFill = "#d9d9d9";
constexpr const char* kWallStroke = "#262626";
constexpr const char* kSlopeStroke = "#9a6b2f";
constexpr const char* kWindowStroke = "#3a8fd6";
constexpr const char* kDoorStroke = "#e37b00";
constexpr const char* kGraphStroke = "#2e9d5b";

constexpr double kMarginPx = 30.0;
constexpr double kTitlePx = 26.0;
constexpr double kFooterPx = 100.0;
constexpr double kDoorWidth_m = 0.9;

std::string num(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", value);
  return buffer;
}


// A storey to draw. Each cell is cut `section_height_m` above its own floor (split levels and
// sloped terrain keep their walls); graph nodes and doors are drawn on the storey whose z band
// holds them.
struct Level {
  int index = -1;  ///< into PlaneMap::storeys, -1 for "everything" when there are none
  std::string title;
  double floor_z = 0.0;
  double cut_z = 0.0;
  double band_lo = 0.0;
  double band_hi = 0.0;
};

// "storey 2" adds nothing to "Storey 2"; other names (e.g. "Ground floor") are shown.
bool informative_name(const std::string& name, std::size_t index) {
  std::string lower;
  for (const char c : name) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return !name.empty() && lower != "storey " + std::to_string(index) &&
         lower != "storey" + std::to_string(index);
}

std::vector<Level> levels_of(const maps::PlaneMap& map, const FloorPlanOptions& options) {
  std::vector<Level> levels;
  const auto& storeys = map.storeys;
  for (std::size_t i = 0; i < storeys.size(); ++i) {
    const auto& s = storeys[i];
    Level level;
    level.index = static_cast<int>(i);
    level.floor_z = s.floor_z;
    level.cut_z = s.floor_z + options.section_height_m;
    level.band_lo = s.floor_z - 0.5;
    level.band_hi = i + 1 < storeys.size() ? storeys[i + 1].floor_z - 0.5 : s.ceiling_z + 0.5;
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "floor at z = %.2f m", s.floor_z);
    level.title = "Storey " + std::to_string(i) +
                  (informative_name(s.name, i) ? " (" + s.name + ")" : "") + ": " + buffer;
    levels.push_back(level);
  }
  if (levels.empty() && !map.bounds.isEmpty()) {  // no storeys known: one plan of everything
    Level level;
    level.floor_z = map.bounds.min().z();
    level.cut_z = level.floor_z + options.section_height_m;
    level.band_lo = -std::numeric_limits<double>::infinity();
    level.band_hi = std::numeric_limits<double>::infinity();
    level.title = "All levels";
    levels.push_back(level);
  }
  return levels;
}

// Maps map-frame xy to pixels of one storey panel; y flipped so north is up.
struct Projection {
  double min_x = 0.0, max_y = 0.0, ppm = 1.0, left = 0.0, top = 0.0;
  double x(double mx) const { return left + (mx - min_x) * ppm; }
  double y(double my) const { return top + (max_y - my) * ppm; }
};

// The largest of 1, 2, 5 x 10^k metres that fits in `max_m`.
double nice_length(double max_m) {
  double best = 1.0;
  for (double decade = 0.01; decade <= 1e5; decade *= 10.0) {
    for (const double step : {1.0, 2.0, 5.0}) {
      if (step * decade <= max_m) best = step * decade;
    }
  }
  return best;
}

bool is_stair(const maps::PlaneMap& map, const maps::Cell& cell) {
  int spanned = 0;
  for (const auto& s : map.storeys) {
    if (cell.floor_z <= s.floor_z + 1.0 && cell.ceiling_z >= s.floor_z + 1.0) ++spanned;
  }
  return spanned > 1;
}

const char* fill_for(const maps::PlaneMap& map, const maps::Cell& cell) {
  if (!cell.navigable) return kNonNavigableFill;
  if (is_stair(map, cell)) return kStairFill;
  if (cell.class_name.find("Connection") != std::string::npos) return kConnectionFill;
  if (cell.class_name.find("Transition") != std::string::npos) return kCorridorFill;
  return kRoomFill;
}

class PlanWriter {
 public:
  PlanWriter(const maps::PlaneMap& map, const FloorPlanOptions& options, std::ostringstream& out)
      : map_(map), options_(options), out_(out) {}

  void storey(const Level& level, std::size_t index, const Projection& proj);

 private:
  // A cell is drawn on its own storey and on every storey whose cut passes through it (stairs).
  bool cell_on(const maps::Cell& cell, const Level& level) const {
    if (level.index < 0) return true;
    return cell.storey == level.index ||
           (cell.floor_z <= level.cut_z && cell.ceiling_z >= level.cut_z);
  }
  // Section height for a polygon on this storey, or NaN when it is not drawn here.
  double cut_height(const maps::PlanarPolygon& polygon, const Level& level) const {
    for (const int c : {polygon.cell, polygon.back_cell}) {
      if (c < 0 || c >= static_cast<int>(map_.cells.size())) continue;
      const auto& cell = map_.cells[static_cast<std::size_t>(c)];
      if (cell_on(cell, level)) {
        return std::max(cell.floor_z, level.floor_z) + options_.section_height_m;
      }
    }
    if (polygon.cell < 0 && polygon.back_cell < 0) return level.cut_z;
    return std::numeric_limits<double>::quiet_NaN();
  }
  bool in_band(const Eigen::Vector3d& p, const Level& level) const {
    return p.z() >= level.band_lo && p.z() < level.band_hi;
  }
  void line(const Projection& proj, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
            const std::string& style) {
    out_ << "<line x1=\"" << num(proj.x(a.x())) << "\" y1=\"" << num(proj.y(a.y())) << "\" x2=\""
         << num(proj.x(b.x())) << "\" y2=\"" << num(proj.y(b.y())) << "\"" << style << "/>\n";
  }
  void doors(const Level& level, const Projection& proj);
  void paths(const Level& level, const Projection& proj);

  const maps::PlaneMap& map_;
  const FloorPlanOptions& options_;
  std::ostringstream& out_;
  std::vector<maps::SectionSegment> walls_;  // this storey's wall cuts, for placing doors
};

void PlanWriter::storey(const Level& level, std::size_t index, const Projection& proj) {
  const double ppm = proj.ppm;
  out_ << "<g class=\"storey\" id=\"storey-" << index << "\">\n";
  out_ << "<text x=\"" << num(proj.left) << "\" y=\"" << num(proj.top - 10.0)
       << "\" font-size=\"14\" font-weight=\"bold\">" << escape_xml(level.title) << "</text>\n";

  out_ << "<g class=\"cells\" stroke=\"#b9b2a4\" stroke-width=\"0.8\">\n";
  for (const auto& cell : map_.cells) {
    if (!cell_on(cell, level) || cell.footprint.size() < 3) continue;
    out_ << "<polygon fill=\"" << fill_for(map_, cell) << "\" points=\"";
    for (const auto& p : cell.footprint)
      out_ << num(proj.x(p.x())) << ',' << num(proj.y(p.y())) << ' ';
    out_ << "\"><title>" << escape_xml(cell.class_name + " " + cell.id) << "</title></polygon>\n";
  }
  out_ << "</g>\n";

  walls_.clear();
  std::vector<maps::SectionSegment> slopes, windows;
  for (const auto& polygon : map_.polygons) {
    const double cut_z = cut_height(polygon, level);
    if (!(polygon.bounds.min().z() <= cut_z && polygon.bounds.max().z() >= cut_z)) continue;
    auto cut = maps::horizontal_section(polygon, cut_z);
    auto& target = polygon.kind == maps::SurfaceKind::Wall ? walls_ : slopes;
    target.insert(target.end(), cut.begin(), cut.end());
    if (polygon.kind == maps::SurfaceKind::Wall) {
      auto openings = maps::horizontal_section_of_holes(polygon, cut_z);
      windows.insert(windows.end(), openings.begin(), openings.end());
    }
  }
  const std::string wall_width = num(std::clamp(0.15 * ppm, 2.0, 6.0));
  out_ << "<g class=\"slopes\" stroke=\"" << kSlopeStroke << "\" stroke-width=\""
       << num(std::clamp(0.05 * ppm, 1.0, 2.5)) << "\" stroke-dasharray=\"6 3\">\n";
  for (const auto& s : slopes) line(proj, s.a, s.b, "");
  out_ << "</g>\n<g class=\"walls\" stroke=\"" << kWallStroke << "\" stroke-width=\"" << wall_width
       << "\" stroke-linecap=\"square\">\n";
  for (const auto& s : walls_) line(proj, s.a, s.b, "");
  out_ << "</g>\n<g class=\"windows\" stroke-linecap=\"butt\">\n";
  for (const auto& s : windows) {  // glazing: a light band with a thin pane line
    line(proj, s.a, s.b, " stroke=\"#ffffff\" stroke-width=\"" + wall_width + "\"");
    line(proj, s.a, s.b, " stroke=\"" + std::string(kWindowStroke) + "\" stroke-width=\"1.5\"");
  }
  out_ << "</g>\n";

  if (options_.show_navigation) doors(level, proj);

  if (options_.show_labels) {
    const double font = std::clamp(0.32 * ppm, 8.0, 13.0);
    out_ << "<g class=\"labels\" font-size=\"" << num(font)
         << "\" text-anchor=\"middle\" fill=\"#3d3d3d\">\n";
    for (const auto& cell : map_.cells) {
      if (!cell_on(cell, level)) continue;
      const auto& p = cell.representative_point;
      out_ << "<text x=\"" << num(proj.x(p.x())) << "\" y=\"" << num(proj.y(p.y()) - 6.0) << "\">"
           << escape_xml(cell.name.empty() ? cell.id : cell.name) << "</text>\n";
    }
    out_ << "</g>\n";
  }
  paths(level, proj);
  out_ << "</g>\n";
}

void PlanWriter::paths(const Level& level, const Projection& proj) {
  if (options_.paths.empty()) return;
  out_ << "<g class=\"paths\" fill=\"none\" stroke-linejoin=\"round\">\n";
  for (const auto& path : options_.paths) {
    // One polyline per run of consecutive points on this storey.
    std::string run;
    std::size_t run_points = 0;
    const auto flush = [&] {
      if (run_points >= 2) {
        out_ << "<polyline stroke=\"" << escape_xml(path.colour) << "\" stroke-width=\""
             << num(path.width_px) << "\"" << (path.dashed ? " stroke-dasharray=\"5 3\"" : "")
             << " points=\"" << run << "\"/>\n";
      }
      run.clear();
      run_points = 0;
    };
    for (const auto& p : path.points) {
      if (!p.allFinite() || !in_band(p, level)) {
        flush();
        continue;
      }
      run += num(proj.x(p.x())) + "," + num(proj.y(p.y())) + " ";
      ++run_points;
    }
    flush();
  }
  out_ << "</g>\n";
}

void PlanWriter::doors(const Level& level, const Projection& proj) {
  const auto& nav = map_.navigation;
  // A node is drawn with its cell's storey, else where its height puts it.
  auto node_in_band = [&](int i) {
    if (i < 0 || i >= static_cast<int>(nav.nodes.size())) return false;
    const auto& node = nav.nodes[static_cast<std::size_t>(i)];
    if (node.cell >= 0 && node.cell < static_cast<int>(map_.cells.size()) && level.index >= 0 &&
        map_.cells[static_cast<std::size_t>(node.cell)].storey == level.index) {
      return true;
    }
    return in_band(node.position, level);
  };
  const std::string graph_style =
      " stroke=\"" + std::string(kGraphStroke) + "\" stroke-width=\"1.3\" stroke-dasharray=\"4 3\"";
  out_ << "<g class=\"navigation\" fill=\"none\">\n";
  for (const auto& edge : nav.edges) {
    const bool from_in = node_in_band(edge.from);
    const bool to_in = node_in_band(edge.to);
    if (edge.through_door) {
      if (!in_band(edge.door_point, level)) continue;
      if (from_in) line(proj, nav.nodes[edge.from].position, edge.door_point, graph_style);
      if (to_in) line(proj, nav.nodes[edge.to].position, edge.door_point, graph_style);
    } else if (from_in && to_in) {
      line(proj, nav.nodes[edge.from].position, nav.nodes[edge.to].position, graph_style);
    }
  }
  out_ << "</g>\n<g class=\"doors\" stroke=\"" << kDoorStroke << "\" stroke-width=\""
       << num(std::clamp(0.12 * proj.ppm, 2.0, 5.0)) << "\" fill=\"" << kDoorStroke << "\">\n";
  for (const auto& edge : nav.edges) {
    if (!edge.through_door || !in_band(edge.door_point, level)) continue;
    // Lay the door along the wall it pierces: of the wall cuts within 1 m, the one whose line
    // passes closest to the door point (the reveals of thick walls run across the door instead).
    const Eigen::Vector2d door = edge.door_point.head<2>();
    double best_line = std::numeric_limits<double>::infinity();
    const maps::SectionSegment* wall = nullptr;
    for (const auto& s : walls_) {
      const Eigen::Vector2d a = s.a.head<2>(), ab = s.b.head<2>() - a;
      const double length2 = ab.squaredNorm();
      if (length2 < 1e-8) continue;
      const double t = std::clamp((door - a).dot(ab) / length2, 0.0, 1.0);
      if ((a + t * ab - door).norm() > 1.0) continue;
      const double line_distance =
          std::abs(ab.x() * (door - a).y() - ab.y() * (door - a).x()) / std::sqrt(length2);
      if (line_distance < best_line) {
        best_line = line_distance;
        wall = &s;
      }
    }
    if (wall != nullptr) {
      const Eigen::Vector2d a = wall->a.head<2>();
      const Eigen::Vector2d u = (wall->b.head<2>() - a).normalized();
      const Eigen::Vector2d c = a + (door - a).dot(u) * u;
      const Eigen::Vector3d p0(c.x() - 0.5 * kDoorWidth_m * u.x(),
                               c.y() - 0.5 * kDoorWidth_m * u.y(), 0);
      const Eigen::Vector3d p1(c.x() + 0.5 * kDoorWidth_m * u.x(),
                               c.y() + 0.5 * kDoorWidth_m * u.y(), 0);
      line(proj, p0, p1, "");
    } else {
      out_ << "<circle cx=\"" << num(proj.x(door.x())) << "\" cy=\"" << num(proj.y(door.y()))
           << "\" r=\"" << num(std::max(3.0, 0.3 * proj.ppm)) << "\"/>\n";
    }
  }
  out_ << "</g>\n<g class=\"nodes\" fill=\"" << kGraphStroke << "\">\n";
  for (std::size_t i = 0; i < nav.nodes.size(); ++i) {
    if (!node_in_band(static_cast<int>(i))) continue;
    const auto& p = nav.nodes[i].position;
    out_ << "<circle cx=\"" << num(proj.x(p.x())) << "\" cy=\"" << num(proj.y(p.y())) << "\" r=\""
         << num(std::clamp(0.12 * proj.ppm, 2.5, 5.0)) << "\"/>\n";
  }
  out_ << "</g>\n";
}

void legend(std::ostringstream& out, double left, double top, double right, double ppm,
            double width_m, const std::vector<PlanPath>& paths) {
  // Scale bar: a nice length of at most a third of the plan width, in alternating halves.
  const double length_m = nice_length(std::max(width_m / 3.0, 0.01));
  const double length_px = length_m * ppm;
  char length_label[32];
  std::snprintf(length_label, sizeof length_label, "%g", length_m);
  out << "<g class=\"scale-bar\" font-size=\"11\">\n"
      << "<rect x=\"" << num(left) << "\" y=\"" << num(top) << "\" width=\"" << num(length_px / 2)
      << "\" height=\"6\" fill=\"#262626\"/>\n"
      << "<rect x=\"" << num(left + length_px / 2) << "\" y=\"" << num(top) << "\" width=\""
      << num(length_px / 2) << "\" height=\"6\" fill=\"#ffffff\" stroke=\"#262626\"/>\n"
      << "<text x=\"" << num(left) << "\" y=\"" << num(top + 20) << "\">0</text>\n"
      << "<text x=\"" << num(left + length_px) << "\" y=\"" << num(top + 20)
      << "\" text-anchor=\"middle\">" << length_label << " m</text>\n</g>\n";

  struct Item {
    const char* label;
    const char* colour;
    bool fill;
  };
  const Item items[] = {
      {"room", kRoomFill, true},          {"corridor", kCorridorFill, true},
      {"stair", kStairFill, true},        {"non-navigable", kNonNavigableFill, true},
      {"wall", kWallStroke, false},       {"sloped surface", kSlopeStroke, false},
      {"window", kWindowStroke, false},   {"door", kDoorStroke, false},
      {"navigation", kGraphStroke, false}};
  double x = left + length_px + 40.0;
  out << "<g class=\"legend\" font-size=\"11\">\n";
  for (const auto& item : items) {
    const double item_px = 26.0 + 6.5 * static_cast<double>(std::string(item.label).size());
    if (x + item_px > right) {  // wrap below the scale bar
      x = left;
      top += 30.0;
    }
    if (item.fill) {
      out << "<rect x=\"" << num(x) << "\" y=\"" << num(top - 4)
          << "\" width=\"14\" height=\"12\" fill=\"" << item.colour << "\" stroke=\"#b9b2a4\"/>\n";
    } else {
      out << "<line x1=\"" << num(x) << "\" y1=\"" << num(top + 2) << "\" x2=\"" << num(x + 14)
          << "\" y2=\"" << num(top + 2) << "\" stroke=\"" << item.colour
          << "\" stroke-width=\"3\"/>\n";
    }
    out << "<text x=\"" << num(x + 18) << "\" y=\"" << num(top + 7) << "\">" << item.label
        << "</text>\n";
    x += item_px;
  }
  for (const auto& path : paths) {
    const double item_px = 26.0 + 6.5 * static_cast<double>(path.label.size());
    if (x + item_px > right) {
      x = left;
      top += 30.0;
    }
    out << "<line x1=\"" << num(x) << "\" y1=\"" << num(top + 2) << "\" x2=\"" << num(x + 14)
        << "\" y2=\"" << num(top + 2) << "\" stroke=\"" << escape_xml(path.colour)
        << "\" stroke-width=\"3\"" << (path.dashed ? " stroke-dasharray=\"5 3\"" : "") << "/>\n";
    out << "<text x=\"" << num(x + 18) << "\" y=\"" << num(top + 7) << "\">" << escape_xml(path.label)
        << "</text>\n";
    x += item_px;
  }
  out << "</g>\n";
}

}  // namespace

std::string render_floor_plan_svg(const maps::PlaneMap& map, const FloorPlanOptions& options) {
  Eigen::AlignedBox3d bounds = map.bounds;
  for (const auto& polygon : map.polygons) bounds.extend(polygon.bounds);
  const auto levels = levels_of(map, options);
  std::ostringstream out;
  if (bounds.isEmpty() || levels.empty()) {
    out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
        << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"300\" height=\"60\">\n"
        << "<text x=\"10\" y=\"35\" font-family=\"sans-serif\">empty map</text>\n</svg>\n";
    return out.str();
  }
  const double width_m = std::max(bounds.sizes().x(), 1e-3);
  const double height_m = std::max(bounds.sizes().y(), 1e-3);
  // Storeys in a grid, highest first in reading order; as many columns as bring the figure
  // closest to a landscape page (tall buildings side by side, wide ones stacked).
  const std::size_t n = levels.size();
  std::size_t columns = 1;
  double best_misfit = std::numeric_limits<double>::infinity();
  for (std::size_t c = 1; c <= n; ++c) {
    const double rows = std::ceil(static_cast<double>(n) / static_cast<double>(c));
    const double misfit =
        std::abs(std::log((static_cast<double>(c) * width_m) / (rows * height_m) / 1.4));
    if (misfit < best_misfit - 1e-9) {
      best_misfit = misfit;
      columns = c;
    }
  }
  const std::size_t rows = (n + columns - 1) / columns;
  const double target_px = options.target_width_px * (columns > 1 ? 1.4 : 1.0);
  const double ppm =
      options.pixels_per_m > 0.0
          ? options.pixels_per_m
          : std::clamp(target_px / (static_cast<double>(columns) * width_m), 1.0, 120.0);
  const double panel_w = width_m * ppm + 2 * kMarginPx;
  const double panel_h = height_m * ppm + kTitlePx + kMarginPx;
  const double total_w = std::max(panel_w * static_cast<double>(columns), 760.0);
  // The legend grows by a row for about every four paths listed in it.
  const double footer_px =
      kFooterPx + 30.0 * std::ceil(static_cast<double>(options.paths.size()) / 4.0);
  const double total_h = panel_h * static_cast<double>(rows) + kMarginPx + footer_px;

  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(total_w) << "\" height=\""
      << num(total_h) << "\" viewBox=\"0 0 " << num(total_w) << ' ' << num(total_h)
      << "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n"
      << "<title>Floor plan: " << levels.size() << " storeys, " << map.cells.size()
      << " cells</title>\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";

  PlanWriter writer(map, options, out);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t index = n - 1 - k;  // highest storey first
    Projection proj;
    proj.min_x = bounds.min().x();
    proj.max_y = bounds.max().y();
    proj.ppm = ppm;
    proj.left = kMarginPx + panel_w * static_cast<double>(k % columns);
    proj.top = kMarginPx + kTitlePx + panel_h * static_cast<double>(k / columns);
    writer.storey(levels[index], index, proj);
  }

  // North arrow, top right above the plans.
  const double nx = total_w - kMarginPx - 10.0;
  const double ny = 6.0;
  out << "<g class=\"north-arrow\"><path d=\"M " << num(nx) << ' ' << num(ny) << " L "
      << num(nx - 7) << ' ' << num(ny + 20) << " L " << num(nx) << ' ' << num(ny + 15) << " L "
      << num(nx + 7) << ' ' << num(ny + 20) << " Z\" fill=\"#262626\"/>"
      << "<text x=\"" << num(nx - 12) << "\" y=\"" << num(ny + 18)
      << "\" font-size=\"12\" text-anchor=\"end\">N</text></g>\n";
  legend(out, kMarginPx, total_h - footer_px + 20.0, total_w - kMarginPx, ppm, width_m,
         options.paths);
  char note[96];
  std::snprintf(note, sizeof note, "Walls cut %.2f m above each floor; map frame, north up.",
                options.section_height_m);
  out << "<text class=\"note\" x=\"" << num(kMarginPx) << "\" y=\"" << num(total_h - 12.0)
      << "\" font-size=\"11\" fill=\"#555555\">" << note << "</text>\n";
  out << "</svg>\n";
  return out.str();
}

void write_floor_plan_svg(const maps::PlaneMap& map, const std::string& path,
                          const FloorPlanOptions& options) {
  std::ofstream out(path);
  if (!out) throw InputError(path, "", "cannot write the SVG file");
  out << render_floor_plan_svg(map, options);
  out.flush();
  if (!out) throw InputError(path, "", "write failed");
}

}  // namespace conicloc::io
