#include "sim/indoorgml_writer.hpp"

#include <Eigen/Geometry>
#include <cassert>
#include <cstdio>

#include "io/xml_escape.hpp"
#include "sim/prism_shell.hpp"

namespace conicloc::sim {
namespace {

// Fixed 6 decimals without trailing zeros (as the Python writer): deterministic and compact.
std::string number(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.6f", value);
  std::string text(buffer);
  text.erase(text.find_last_not_of('0') + 1);
  if (text.back() == '.') text.pop_back();
  return text == "-0" ? "0" : text;
}

std::string positions(const maps::Ring3& points) {
  std::string text;
  for (const auto& p : points) {
    for (int i = 0; i < 3; ++i) {
      if (!text.empty()) text += ' ';
      text += number(p[i]);
    }
  }
  return text;
}

// Indented XML, one element per line.
class XmlLines {
 public:
  void raw(const std::string& line) { text_ += line + "\n"; }
  void open(const std::string& tag, const std::string& attributes = "") {
    raw(pad() + "<" + tag + attributes + ">");
    ++depth_;
  }
  void close(const std::string& tag) {
    --depth_;
    raw(pad() + "</" + tag + ">");
  }
  void leaf(const std::string& tag, const std::string& text, const std::string& attributes = "") {
    raw(pad() + "<" + tag + attributes + ">" + io::escape_xml(text) + "</" + tag + ">");
  }
  void link(const std::string& tag, const std::string& target) {
    raw(pad() + "<" + tag + " xlink:href=\"#" + target + "\"/>");
  }
  void ring(const std::string& tag, const std::string& id, maps::Ring3 points) {
    points.push_back(points.front());  // GML rings are closed
    open(tag);
    open("gml:LinearRing", id_attribute(id));
    leaf("gml:posList", positions(points), " srsDimension=\"3\"");
    close("gml:LinearRing");
    close(tag);
  }
  void polygon(const std::string& id, const maps::Ring3& outer,
               const std::vector<maps::Ring3>& holes) {
    open("gml:Polygon", id_attribute(id));
    ring("gml:exterior", id + "-ext", outer);
    for (std::size_t k = 0; k < holes.size(); ++k)
      ring("gml:interior", id + "-int" + std::to_string(k), holes[k]);
    close("gml:Polygon");
  }
  static std::string id_attribute(const std::string& id) { return " gml:id=\"" + id + "\""; }
  std::string take() { return std::move(text_); }

 private:
  std::string pad() const { return std::string(2 * depth_, ' '); }
  std::string text_;
  int depth_ = 0;
};

void write_shell(XmlLines& w, const std::string& cell_id, const std::string& side,
                 const std::vector<ShellPolygon>& shell) {
  w.open("gml:" + side);
  w.open("gml:Shell");
  for (const auto& polygon : shell) {
    w.open("gml:surfaceMember");
    w.polygon(cell_id + "-" + polygon.suffix, polygon.outer, polygon.holes);
    w.close("gml:surfaceMember");
  }
  w.close("gml:Shell");
  w.close("gml:" + side);
}

void write_cell(XmlLines& w, const PrismCell& cell, const std::vector<ShellPolygon>& exterior,
                const std::vector<DoorOpening>& doors) {
  w.open("core:cellSpaceMember");
  w.open(cell.class_name, XmlLines::id_attribute(cell.id));
  w.leaf("gml:description", cell.description);
  w.leaf("gml:name", cell.name);
  w.open("core:cellSpaceGeometry");
  w.open("core:Geometry3D");
  w.open("gml:Solid", XmlLines::id_attribute(cell.id + "-solid"));
  write_shell(w, cell.id, "exterior", exterior);
  for (const auto& shell : pillar_shells(cell)) write_shell(w, cell.id, "interior", shell);
  w.close("gml:Solid");
  w.close("core:Geometry3D");
  w.close("core:cellSpaceGeometry");
  w.link("core:duality", "S-" + cell.id);
  for (const auto& door : doors) {
    if (door.cells[0] == cell.id || door.cells[1] == cell.id)
      w.link("core:partialboundedBy", door.id);
  }
  w.close(cell.class_name);
  w.close("core:cellSpaceMember");
}

void write_door(XmlLines& w, const DoorOpening& door, const PrismBuilding& building) {
  w.open("core:cellSpaceBoundaryMember");
  w.open("navi:ConnectionBoundary", XmlLines::id_attribute(door.id));
  w.leaf("gml:description", "door");
  w.leaf("gml:name", door.name);
  w.link("core:duality", "T-" + door.id);
  w.open("core:cellSpaceBoundaryGeometry");
  w.open("core:geometry3D");
  w.polygon(door.id + "-polygon", door_ring(door, building.cell(door.cells[0])), {});
  w.close("core:geometry3D");
  w.close("core:cellSpaceBoundaryGeometry");
  w.close("navi:ConnectionBoundary");
  w.close("core:cellSpaceBoundaryMember");
}

void write_state(XmlLines& w, const PrismCell& cell, const std::vector<DoorOpening>& doors) {
  w.open("core:stateMember");
  w.open("core:State", XmlLines::id_attribute("S-" + cell.id));
  w.leaf("gml:name", cell.name);
  w.link("core:duality", cell.id);
  for (const auto& door : doors) {
    if (door.cells[0] == cell.id || door.cells[1] == cell.id)
      w.link("core:connects", "T-" + door.id);
  }
  w.open("core:geometry");
  w.open("gml:Point", XmlLines::id_attribute("S-" + cell.id + "-point"));
  w.leaf("gml:pos", positions({cell.state_point()}), " srsDimension=\"3\"");
  w.close("gml:Point");
  w.close("core:geometry");
  w.close("core:State");
  w.close("core:stateMember");
}

// The Transition's line runs from one State through the door's centre (0.5 m above its sill)
// to the other; its length is the weight.
void write_transition(XmlLines& w, const DoorOpening& door, const PrismBuilding& building) {
  const Eigen::Vector2d middle = 0.5 * (door.p0 + door.p1);
  const maps::Ring3 line = {building.cell(door.cells[0]).state_point(),
                            {middle.x(), middle.y(), door.z0 + 0.5},
                            building.cell(door.cells[1]).state_point()};
  const double length = (line[1] - line[0]).norm() + (line[2] - line[1]).norm();
  const std::string id = "T-" + door.id;
  w.open("core:transitionMember");
  w.open("core:Transition", XmlLines::id_attribute(id));
  w.leaf("gml:name", door.name);
  w.leaf("core:weight", number(length));
  w.link("core:connects", "S-" + door.cells[0]);
  w.link("core:connects", "S-" + door.cells[1]);
  w.link("core:duality", door.id);
  w.open("core:geometry");
  w.open("gml:LineString", XmlLines::id_attribute(id + "-line"));
  w.leaf("gml:posList", positions(line), " srsDimension=\"3\"");
  w.close("gml:LineString");
  w.close("core:geometry");
  w.close("core:Transition");
  w.close("core:transitionMember");
}

constexpr const char* kNamespaces =
    " xmlns:core=\"http://www.opengis.net/indoorgml/1.0/core\""
    " xmlns:navi=\"http://www.opengis.net/indoorgml/1.0/navigation\""
    " xmlns:gml=\"http://www.opengis.net/gml/3.2\""
    " xmlns:xlink=\"http://www.w3.org/1999/xlink\""
    " xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\""
    " xsi:schemaLocation=\"http://www.opengis.net/indoorgml/1.0/core"
    " http://schemas.opengis.net/indoorgml/1.0/indoorgmlcore.xsd"
    " http://www.opengis.net/indoorgml/1.0/navigation"
    " http://schemas.opengis.net/indoorgml/1.0/indoorgmlnavi.xsd\""
    " gml:id=\"IFs\"";

}  // namespace

std::string write_indoorgml(const PrismBuilding& building) {
  std::vector<std::vector<ShellPolygon>> shells;
  Eigen::AlignedBox3d envelope;
  for (const auto& cell : building.cells) {
    shells.push_back(exterior_shell(cell, building.doors));
    for (const auto& polygon : shells.back()) {
      for (const auto& p : polygon.outer) envelope.extend(p);
    }
  }

  XmlLines w;
  w.raw("<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
  w.raw("<!--");
  for (const auto& line : building.summary) {
    assert(line.find("--") == std::string::npos);  // XML comments must not hold "--"
    w.raw("  " + line);
  }
  w.raw("-->");
  w.open("core:IndoorFeatures", kNamespaces);
  w.leaf("gml:name", building.name);
  w.open("gml:boundedBy");
  w.open("gml:Envelope", " srsDimension=\"3\"");
  w.leaf("gml:lowerCorner", positions({envelope.min()}));
  w.leaf("gml:upperCorner", positions({envelope.max()}));
  w.close("gml:Envelope");
  w.close("gml:boundedBy");

  w.open("core:primalSpaceFeatures");
  w.open("core:PrimalSpaceFeatures", XmlLines::id_attribute("PSF"));
  for (std::size_t c = 0; c < building.cells.size(); ++c)
    write_cell(w, building.cells[c], shells[c], building.doors);
  for (const auto& door : building.doors) write_door(w, door, building);
  w.close("core:PrimalSpaceFeatures");
  w.close("core:primalSpaceFeatures");

  w.open("core:multiLayeredGraph");
  w.open("core:MultiLayeredGraph", XmlLines::id_attribute("MLG"));
  w.open("core:spaceLayers", XmlLines::id_attribute("SLs"));
  w.open("core:spaceLayerMember");
  w.open("core:SpaceLayer", XmlLines::id_attribute("TopographicLayer"));
  w.open("core:nodes", XmlLines::id_attribute("Nodes"));
  for (const auto& cell : building.cells) write_state(w, cell, building.doors);
  w.close("core:nodes");
  w.open("core:edges", XmlLines::id_attribute("Edges"));
  for (const auto& door : building.doors) write_transition(w, door, building);
  w.close("core:edges");
  w.close("core:SpaceLayer");
  w.close("core:spaceLayerMember");
  w.close("core:spaceLayers");
  w.close("core:MultiLayeredGraph");
  w.close("core:multiLayeredGraph");
  w.close("core:IndoorFeatures");
  return w.take();
}

}  // namespace conicloc::sim
