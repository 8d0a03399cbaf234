#include "io/gml_geometry.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>

#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

constexpr int kMaxHrefDepth = 32;
constexpr double kMaxCoordinateMagnitude = 1e9;  // file units

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',';
}

// Local part of an attribute's name ("gml:id" -> "id"), for messages only.
std::string_view local_part(const char* name) {
  const std::string_view view(name);
  const auto colon = view.find(':');
  return colon == std::string_view::npos ? view : view.substr(colon + 1);
}

// Nearest gml:id at or above `node`, by attribute name only (for messages, no scope needed).
std::pair<pugi::xml_node, std::string> nearest_id(pugi::xml_node node) {
  for (pugi::xml_node n = node; n && n.type() == pugi::node_element; n = n.parent()) {
    for (const pugi::xml_attribute attribute : n.attributes()) {
      const std::string_view name(attribute.name());
      if (name.find(':') != std::string_view::npos && local_part(attribute.name()) == "id" &&
          name.substr(0, 6) != "xmlns:") {
        return {n, attribute.value()};
      }
    }
  }
  return {};
}

void index_recursive(pugi::xml_node node, const NamespaceScope* parent_scope, IdIndex& index,
                     std::vector<std::string>& duplicates) {
  const NamespaceScope scope(parent_scope, node);
  if (const pugi::xml_attribute id = scope.attribute(node, ns::kGml, "id")) {
    if (!index.emplace(std::string_view(id.value()), node).second) {
      duplicates.emplace_back(id.value());
    }
  }
  for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
    if (child.type() == pugi::node_element) index_recursive(child, &scope, index, duplicates);
  }
}

bool has_element_children(pugi::xml_node node) {
  for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
    if (child.type() == pugi::node_element) return true;
  }
  return false;
}

// srsDimension stated on `node` or its ancestors (for xlink targets read out of context).
int inherited_dimension(pugi::xml_node node) {
  for (pugi::xml_node n = node; n && n.type() == pugi::node_element; n = n.parent()) {
    const int dimension = n.attribute("srsDimension").as_int(0);
    if (dimension != 0) return dimension;
  }
  return 0;
}

}  // namespace

IdIndex index_gml_ids(const pugi::xml_document& document, std::vector<std::string>& duplicates) {
  IdIndex index;
  if (const pugi::xml_node root = document.document_element()) {
    index_recursive(root, nullptr, index, duplicates);
  }
  return index;
}

maps::SourcePlace GmlReader::place(pugi::xml_node node, const NamespaceScope& scope) const {
  maps::SourcePlace out;
  out.line = source_.line_of(node);
  out.element = std::string(scope.resolve_element(node.name()).local);
  const auto [owner, id] = nearest_id(node);
  out.id = id;
  if (owner && owner != node)
    out.element += std::string(" in ") + std::string(local_part(owner.name()));
  return out;
}

void GmlReader::fail(pugi::xml_node node, const NamespaceScope& scope,
                     const std::string& what) const {
  throw InputError(source_.path(), maps::describe(place(node, scope)), what);
}

int GmlReader::dimension_at(pugi::xml_node node, int inherited) {
  if (building_.crs.empty()) {
    if (const pugi::xml_attribute name = node.attribute("srsName")) building_.crs = name.value();
  }
  const pugi::xml_attribute attribute = node.attribute("srsDimension");
  if (!attribute) return inherited;
  const int dimension = attribute.as_int(0);
  if (dimension != 2 && dimension != 3) {
    const NamespaceScope scope(nullptr, node);
    fail(node, scope,
         std::string("srsDimension must be 2 or 3, not \"") + attribute.value() + "\"");
  }
  return dimension;
}

void GmlReader::parse_numbers(pugi::xml_node element, const NamespaceScope& scope,
                              std::string_view text, std::vector<double>& values) const {
  const char* p = text.data();
  const char* end = text.data() + text.size();
  while (true) {
    while (p < end && is_space(*p)) ++p;
    if (p >= end) break;
    const char* token_end = p;
    while (token_end < end && !is_space(*token_end)) ++token_end;
    double value = 0.0;
    const char* start = (*p == '+') ? p + 1 : p;  // from_chars rejects a leading '+'
    const auto [ptr, error] = std::from_chars(start, token_end, value);
    if (error != std::errc{} || ptr != token_end) {
      fail(element, scope, "not a number: \"" + std::string(p, token_end) + "\"");
    }
    if (!std::isfinite(value)) {
      fail(element, scope,
           "coordinate is not a finite number: \"" + std::string(p, token_end) + "\"");
    }
    // Beyond this no CRS a building is drawn in makes sense (1e9 m is 150 Earth radii), and
    // the plane geometry (cross products, squared norms) would overflow to infinity.
    if (std::abs(value) > kMaxCoordinateMagnitude) {
      fail(element, scope,
           "coordinate " + std::string(p, token_end) + " is out of range (|value| > 1e9)");
    }
    values.push_back(value);
    p = token_end;
  }
}

maps::Ring3 GmlReader::read_points(pugi::xml_node geometry, const NamespaceScope& parent_scope,
                                   int srs_dimension) {
  const NamespaceScope scope(&parent_scope, geometry);
  srs_dimension = dimension_at(geometry, srs_dimension);
  maps::Ring3 points;
  std::vector<double> values;
  bool any_coordinates = false;
  auto append = [&](const std::vector<double>& v, int dimension) {
    for (std::size_t i = 0; i + dimension <= v.size(); i += dimension) {
      points.emplace_back(v[i], v[i + 1], dimension == 3 ? v[i + 2] : 0.0);
    }
  };
  for (pugi::xml_node child = geometry.first_child(); child; child = child.next_sibling()) {
    if (child.type() != pugi::node_element) continue;
    const NamespaceScope child_scope(&scope, child);
    const QName name = child_scope.resolve_element(child.name());
    if (!ns::is_gml(name.uri)) continue;
    if (name.local == "pos" || name.local == "posList" || name.local == "coordinates") {
      any_coordinates = true;
      values.clear();
      parse_numbers(child, child_scope, child.child_value(), values);
      int dimension = dimension_at(child, srs_dimension);
      if (values.empty()) fail(child, child_scope, "missing coordinates");
      if (name.local == "pos" && dimension == 0) dimension = static_cast<int>(values.size());
      if (name.local == "coordinates") {
        // "x,y[,z] x,y[,z] ...": the tuple length is the count of commas in the first tuple + 1.
        const std::string_view text(child.child_value());
        const auto first = text.find_first_not_of(" \t\r\n");
        const auto tuple_end = text.find_first_of(" \t\r\n", first);
        const std::string_view tuple = text.substr(first, tuple_end - first);
        dimension = static_cast<int>(std::count(tuple.begin(), tuple.end(), ',')) + 1;
      }
      if (dimension == 0) {  // posList without srsDimension: the count attribute, else infer
        const int count = child.attribute("count").as_int(0);
        const auto n = static_cast<int>(values.size());
        if (count > 0 && n % count == 0) {
          dimension = n / count;
        } else if (n % 3 == 0 && n % 2 != 0) {
          dimension = 3;
        } else if (n % 2 == 0 && n % 3 != 0) {
          dimension = 2;
        } else {
          // Both fit (6, 12, ...): a closed ring repeats its first point; prefer 3 when it does.
          const bool closes_3 = values[0] == values[n - 3] && values[1] == values[n - 2] &&
                                values[2] == values[n - 1];
          const bool closes_2 = values[0] == values[n - 2] && values[1] == values[n - 1];
          dimension = (closes_2 && !closes_3) ? 2 : 3;
        }
      }
      if (dimension != 2 && dimension != 3) {
        fail(child, child_scope,
             "cannot use " + std::to_string(values.size()) + " values as 2D or 3D coordinates");
      }
      if (values.size() % static_cast<std::size_t>(dimension) != 0) {
        fail(child, child_scope,
             std::to_string(values.size()) + " values do not divide into points of dimension " +
                 std::to_string(dimension));
      }
      append(values, dimension);
    } else if (name.local == "pointProperty" || name.local == "pointRep" || name.local == "Point") {
      const maps::Ring3 more = read_first_points(child, child_scope, srs_dimension);
      if (more.empty()) continue;
      any_coordinates = true;
      points.insert(points.end(), more.begin(), more.end());
    }
  }
  if (!any_coordinates) fail(geometry, scope, "missing coordinates");
  return points;
}

maps::Ring3 GmlReader::read_first_points(pugi::xml_node node, const NamespaceScope& parent_scope,
                                         int srs_dimension) {
  const NamespaceScope scope(&parent_scope, node);
  srs_dimension = dimension_at(node, srs_dimension);
  const QName name = scope.resolve_element(node.name());
  if (ns::is_gml(name.uri) && (name.local == "Point" || name.local == "LineString" ||
                               name.local == "LinearRing" || name.local == "LineStringSegment")) {
    return read_points(node, parent_scope, srs_dimension);
  }
  for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
    if (child.type() != pugi::node_element) continue;
    maps::Ring3 points = read_first_points(child, scope, srs_dimension);
    if (!points.empty()) return points;
  }
  return {};
}

void GmlReader::read_polygon(pugi::xml_node polygon, const NamespaceScope& parent_scope,
                             int srs_dimension, bool reversed, std::vector<maps::RawPolygon>& out) {
  const NamespaceScope scope(&parent_scope, polygon);
  srs_dimension = dimension_at(polygon, srs_dimension);
  maps::RawPolygon raw;
  raw.place = place(polygon, scope);
  bool has_exterior = false;
  for (pugi::xml_node child = polygon.first_child(); child; child = child.next_sibling()) {
    if (child.type() != pugi::node_element) continue;
    const NamespaceScope child_scope(&scope, child);
    const QName name = child_scope.resolve_element(child.name());
    if (!ns::is_gml(name.uri)) continue;
    const bool exterior = name.local == "exterior" || name.local == "outerBoundaryIs";
    const bool interior = name.local == "interior" || name.local == "innerBoundaryIs";
    if (!exterior && !interior) continue;
    const int ring_dimension = dimension_at(child, srs_dimension);
    maps::Ring3 ring;
    for (pugi::xml_node ring_node = child.first_child(); ring_node;
         ring_node = ring_node.next_sibling()) {
      if (ring_node.type() != pugi::node_element) continue;
      const QName ring_name = child_scope.resolve_element(ring_node.name());
      if (ring_name.local == "LinearRing") {
        ring = read_points(ring_node, child_scope, ring_dimension);
        if (raw.place.id.empty() || raw.place.element != "Polygon") {
          if (const auto id = child_scope.attribute(ring_node, ns::kGml, "id")) {
            if (raw.id.empty()) raw.id = id.value();
          }
        }
      } else {  // gml:Ring of curve members: concatenate their points
        ring = read_first_points(ring_node, child_scope, ring_dimension);
      }
    }
    if (exterior) {
      if (has_exterior) fail(child, child_scope, "polygon with two exterior rings");
      has_exterior = true;
      raw.outer = std::move(ring);
    } else {
      raw.holes.push_back(std::move(ring));
    }
  }
  if (!has_exterior) fail(polygon, scope, "polygon without an exterior ring");
  if (const auto id = scope.attribute(polygon, ns::kGml, "id")) raw.id = id.value();
  if (raw.id.empty()) raw.id = raw.place.id;
  if (reversed) {
    std::reverse(raw.outer.begin(), raw.outer.end());
    for (auto& hole : raw.holes) std::reverse(hole.begin(), hole.end());
  }
  ++building_.polygons_read;
  out.push_back(std::move(raw));
}

void GmlReader::follow_href(pugi::xml_node reference, const NamespaceScope& scope,
                            int /*srs_dimension*/, bool reversed,
                            std::vector<maps::RawPolygon>& out) {
  const pugi::xml_attribute href = scope.attribute(reference, ns::kXlink, "href");
  std::string_view target_id(href.value());
  if (const auto hash = target_id.find('#'); hash != std::string_view::npos) {
    target_id = target_id.substr(hash + 1);
  }
  const auto it = ids_.find(target_id);
  if (it == ids_.end()) {
    fail(reference, scope,
         "broken xlink:href \"" + std::string(href.value()) + "\": no element has that gml:id");
  }
  if (href_depth_ >= kMaxHrefDepth) fail(reference, scope, "xlink:href chain too deep (a cycle?)");
  ++href_depth_;
  const std::vector<NamespaceScope> chain = NamespaceScope::chain_for(it->second.parent());
  const NamespaceScope root_scope(nullptr, pugi::xml_node{});
  read_surfaces(it->second, chain.empty() ? root_scope : chain.back(),
                inherited_dimension(it->second), reversed, out);
  --href_depth_;
}

void GmlReader::read_surfaces(pugi::xml_node geometry, const NamespaceScope& parent_scope,
                              int srs_dimension, bool reversed,
                              std::vector<maps::RawPolygon>& out) {
  const NamespaceScope scope(&parent_scope, geometry);
  srs_dimension = dimension_at(geometry, srs_dimension);
  const QName name = scope.resolve_element(geometry.name());
  if (ns::is_gml(name.uri)) {
    if (name.local == "Polygon" || name.local == "PolygonPatch" || name.local == "Triangle" ||
        name.local == "Rectangle") {
      read_polygon(geometry, parent_scope, srs_dimension, reversed, out);
      return;
    }
    if (name.local == "OrientableSurface") {
      const std::string_view orientation(geometry.attribute("orientation").as_string("+"));
      if (orientation == "-") reversed = !reversed;
    }
    if (name.local == "boundedBy" || name.local == "name" || name.local == "description") return;
  }
  if (!has_element_children(geometry) && scope.attribute(geometry, ns::kXlink, "href")) {
    follow_href(geometry, parent_scope, srs_dimension, reversed, out);
    return;
  }
  for (pugi::xml_node child = geometry.first_child(); child; child = child.next_sibling()) {
    if (child.type() == pugi::node_element) {
      read_surfaces(child, scope, srs_dimension, reversed, out);
    }
  }
}

std::vector<maps::RawShell> GmlReader::read_shells(pugi::xml_node geometry,
                                                   const NamespaceScope& parent_scope,
                                                   int srs_dimension) {
  const NamespaceScope scope(&parent_scope, geometry);
  srs_dimension = dimension_at(geometry, srs_dimension);
  const QName name = scope.resolve_element(geometry.name());
  std::vector<maps::RawShell> shells;
  if (ns::is_gml(name.uri) && name.local == "Solid") {
    for (pugi::xml_node child = geometry.first_child(); child; child = child.next_sibling()) {
      if (child.type() != pugi::node_element) continue;
      const QName child_name = scope.resolve_element(child.name());
      if (!ns::is_gml(child_name.uri)) continue;
      if (child_name.local != "exterior" && child_name.local != "interior") continue;
      maps::RawShell shell;
      shell.interior = child_name.local == "interior";
      read_surfaces(child, scope, srs_dimension, false, shell.polygons);
      shells.push_back(std::move(shell));
    }
    return shells;
  }
  if (ns::is_gml(name.uri) && (name.local == "CompositeSolid" || name.local == "MultiSolid" ||
                               name.local == "solidMember" || name.local == "solidMembers")) {
    for (pugi::xml_node child = geometry.first_child(); child; child = child.next_sibling()) {
      if (child.type() != pugi::node_element) continue;
      auto more = read_shells(child, scope, srs_dimension);
      for (auto& shell : more) shells.push_back(std::move(shell));
    }
    return shells;
  }
  maps::RawShell shell;
  read_surfaces(geometry, parent_scope, srs_dimension, false, shell.polygons);
  if (!shell.polygons.empty()) shells.push_back(std::move(shell));
  return shells;
}

}  // namespace conicloc::io
