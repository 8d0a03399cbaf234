#include "io/indoorgml_structure.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "io/gml_geometry.hpp"
#include "io/input_error.hpp"
#include "io/xml_namespace_scope.hpp"

namespace conicloc::io {
namespace {

enum class MemberKind { Cell, Boundary, State, Transition, None };

MemberKind member_kind(std::string_view local) {
  if (local == "cellSpaceMember") return MemberKind::Cell;
  if (local == "cellSpaceBoundaryMember" || local == "cellBoundaryMember") {
    return MemberKind::Boundary;
  }
  if (local == "stateMember" || local == "nodeMember") return MemberKind::State;
  if (local == "transitionMember" || local == "edgeMember") return MemberKind::Transition;
  return MemberKind::None;
}

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// Wrappers between a feature and its GML geometry, in all versions:
// cellSpaceGeometry/Geometry3D (1.0.3), Geometry3D (1.0.1), cellSpaceGeom/CellSpaceGeometry/
// geometry3D (2.0), cellSpaceBoundaryGeometry/geometry3D|geometry2D, State/Transition geometry.
bool is_geometry_wrapper(std::string_view local) {
  const std::string name = lower(local);
  return name.find("geometry") != std::string::npos || name == "cellspacegeom";
}

std::string_view href_id(const char* href) {
  std::string_view id(href);
  if (const auto hash = id.find('#'); hash != std::string_view::npos) id = id.substr(hash + 1);
  return id;
}

bool is_layer(std::string_view local) {
  return local == "SpaceLayer" || local == "ThematicLayer";
}

bool is_non_navigable(std::string_view class_name, std::string_view uri) {
  const std::string name = lower(class_name);
  return name.find("nonnavigable") != std::string::npos ||
         lower(uri).find("nonnavi") != std::string::npos;
}

class StructureWalker {
 public:
  StructureWalker(const XmlSource& source, const IdIndex& ids, maps::RawBuilding& building)
      : source_(source), building_(building), gml_(source, ids, building) {}

  void walk(pugi::xml_node node, const NamespaceScope& parent_scope) {
    const NamespaceScope scope(&parent_scope, node);
    const QName name = scope.resolve_element(node.name());
    if (ns::is_gml(name.uri)) {
      if (name.local == "boundedBy") record_srs_name(node);
      return;
    }
    const bool layer = ns::is_indoorgml(name.uri) && is_layer(name.local) &&
                       !scope.attribute(node, ns::kXlink, "href");
    if (layer) {
      // The states (2.0: the cells too) below belong to this layer; layers do not nest.
      read_layer(node, scope);
      layer_ = building_.layers.back().id;
    }
    const MemberKind kind = ns::is_indoorgml(name.uri) ? member_kind(name.local) : MemberKind::None;
    for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
      if (child.type() != pugi::node_element) continue;
      switch (kind) {
        case MemberKind::Cell:
          read_cell(child, scope);
          break;
        case MemberKind::Boundary:
          read_boundary(child, scope);
          break;
        case MemberKind::State:
          read_state(child, scope);
          break;
        case MemberKind::Transition:
          read_transition(child, scope);
          break;
        case MemberKind::None:
          walk(child, scope);
          break;
      }
    }
    if (layer) layer_.clear();
  }

  bool saw_direct_geometry() const { return direct_geometry_; }

 private:
  void record_srs_name(pugi::xml_node node) {
    if (!building_.crs.empty()) return;
    const pugi::xml_node found =
        node.find_node([](pugi::xml_node n) { return static_cast<bool>(n.attribute("srsName")); });
    if (found) building_.crs = found.attribute("srsName").value();
  }

  maps::SourcePlace feature_place(pugi::xml_node node, const NamespaceScope& scope,
                                  std::string& id_out) {
    if (const auto id = scope.attribute(node, ns::kGml, "id")) id_out = id.value();
    maps::SourcePlace place;
    place.line = source_.line_of(node);
    place.element = std::string(scope.resolve_element(node.name()).local);
    place.id = id_out;
    return place;
  }

  // Calls `visit(child, child_scope, name)` for every element child of `node`.
  template <typename Visit>
  void for_children(pugi::xml_node node, const NamespaceScope& scope, Visit&& visit) {
    for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
      if (child.type() != pugi::node_element) continue;
      const NamespaceScope child_scope(&scope, child);
      visit(child, child_scope, child_scope.resolve_element(child.name()));
    }
  }

  std::string href_of(pugi::xml_node node, const NamespaceScope& scope) {
    return std::string(href_id(scope.attribute(node, ns::kXlink, "href").value()));
  }

  // Descends through wrapper elements to the GML geometry of a cell.
  void read_cell_geometry(pugi::xml_node wrapper, const NamespaceScope& scope, bool two_d,
                          maps::RawCell& cell) {
    for_children(
        wrapper, scope,
        [&](pugi::xml_node child, const NamespaceScope& child_scope, const QName& name) {
          if (ns::is_gml(name.uri)) {
            if (name.local == "boundedBy" || name.local == "name" || name.local == "description") {
              return;
            }
            if (two_d) {
              gml_.read_surfaces(child, scope, 0, false, cell.footprints_2d);
            } else {
              for (auto& shell : gml_.read_shells(child, scope, 0))
                cell.shells.push_back(std::move(shell));
            }
            return;
          }
          read_cell_geometry(child, child_scope,
                             two_d || lower(name.local).find("2d") != std::string::npos, cell);
        });
  }

  void read_cell(pugi::xml_node node, const NamespaceScope& parent_scope) {
    const NamespaceScope scope(&parent_scope, node);
    if (scope.attribute(node, ns::kXlink, "href")) return;  // a reference to a cell held elsewhere
    maps::RawCell cell;
    cell.place = feature_place(node, scope, cell.id);
    const QName name = scope.resolve_element(node.name());
    cell.class_name = std::string(name.local);
    cell.namespace_uri = std::string(name.uri);
    cell.navigable = !is_non_navigable(name.local, name.uri);
    cell.layer = layer_;
    for_children(
        node, scope,
        [&](pugi::xml_node child, const NamespaceScope& child_scope, const QName& child_name) {
          if (ns::is_gml(child_name.uri)) {
            if (child_name.local == "name" && cell.name.empty()) cell.name = child.child_value();
            return;
          }
          if (child_name.local == "duality") {
            cell.state_id = href_of(child, child_scope);
          } else if (child_name.local == "partialboundedBy" || child_name.local == "boundedBy" ||
                     child_name.local == "cellSpaceBoundaryMember") {
            if (child.first_child().type() == pugi::node_element) {
              for_children(child, child_scope,
                           [&](pugi::xml_node boundary, const NamespaceScope&, const QName&) {
                             read_boundary(boundary, child_scope);
                             cell.boundary_ids.push_back(building_.boundaries.back().id);
                           });
            } else {
              cell.boundary_ids.push_back(href_of(child, child_scope));
            }
          } else if (is_geometry_wrapper(child_name.local)) {
            const std::string local = lower(child_name.local);
            if (local == "geometry3d" || local == "geometry2d") direct_geometry_ = true;
            read_cell_geometry(child, child_scope, local.find("2d") != std::string::npos, cell);
          }
        });
    building_.cells.push_back(std::move(cell));
  }

  // Boundary geometry: polygons (3D) or curves (2D), below any wrapper.
  void read_boundary_geometry(pugi::xml_node wrapper, const NamespaceScope& scope,
                              maps::RawBoundary& boundary) {
    for_children(wrapper, scope,
                 [&](pugi::xml_node child, const NamespaceScope& child_scope, const QName& name) {
                   if (!ns::is_gml(name.uri)) {
                     read_boundary_geometry(child, child_scope, boundary);
                   } else if (name.local == "LineString" || name.local == "Curve" ||
                              name.local == "MultiCurve" || name.local == "CompositeCurve") {
                     maps::Ring3 line = gml_.read_first_points(child, scope, 0);
                     if (!line.empty()) boundary.lines.push_back(std::move(line));
                   } else if (name.local != "boundedBy" && name.local != "name" &&
                              name.local != "description") {
                     gml_.read_surfaces(child, scope, 0, false, boundary.polygons);
                   }
                 });
  }

  void read_boundary(pugi::xml_node node, const NamespaceScope& parent_scope) {
    const NamespaceScope scope(&parent_scope, node);
    if (scope.attribute(node, ns::kXlink, "href")) return;
    maps::RawBoundary boundary;
    boundary.place = feature_place(node, scope, boundary.id);
    boundary.class_name = std::string(scope.resolve_element(node.name()).local);
    for_children(node, scope,
                 [&](pugi::xml_node child, const NamespaceScope& child_scope, const QName& name) {
                   if (ns::is_gml(name.uri)) return;
                   if (name.local == "duality") {
                     boundary.transition_id = href_of(child, child_scope);
                   } else if (is_geometry_wrapper(name.local)) {
                     read_boundary_geometry(child, child_scope, boundary);
                   }
                 });
    // Boundary polygons are not cell surfaces: keep them out of the cell polygon count.
    building_.polygons_read -= static_cast<int>(boundary.polygons.size());
    building_.boundaries.push_back(std::move(boundary));
  }

  // SpaceLayer (1.0: its class) or ThematicLayer (2.0: its theme, Physical or Virtual).
  void read_layer(pugi::xml_node node, const NamespaceScope& scope) {
    maps::RawLayer layer;
    layer.place = feature_place(node, scope, layer.id);
    if (layer.id.empty()) layer.id = maps::describe(layer.place);
    for_children(node, scope, [&](pugi::xml_node child, const NamespaceScope&, const QName& name) {
      if (ns::is_indoorgml(name.uri) && (name.local == "class" || name.local == "theme"))
        layer.layer_class = child.child_value();
    });
    building_.layers.push_back(std::move(layer));
  }

  void read_state(pugi::xml_node node, const NamespaceScope& parent_scope) {
    const NamespaceScope scope(&parent_scope, node);
    if (scope.attribute(node, ns::kXlink, "href")) return;
    maps::RawState state;
    state.place = feature_place(node, scope, state.id);
    state.layer = layer_;
    state.class_name = std::string(scope.resolve_element(node.name()).local);
    for_children(node, scope,
                 [&](pugi::xml_node child, const NamespaceScope& child_scope, const QName& name) {
                   if (ns::is_gml(name.uri)) return;
                   if (name.local == "duality") {
                     state.cell_id = href_of(child, child_scope);
                   } else if (is_geometry_wrapper(name.local)) {
                     const maps::Ring3 points = gml_.read_first_points(child, scope, 0);
                     if (!points.empty()) state.point = points.front();
                   }
                 });
    building_.states.push_back(std::move(state));
  }

  void read_transition(pugi::xml_node node, const NamespaceScope& parent_scope) {
    const NamespaceScope scope(&parent_scope, node);
    if (scope.attribute(node, ns::kXlink, "href")) return;
    maps::RawTransition transition;
    transition.place = feature_place(node, scope, transition.id);
    for_children(node, scope,
                 [&](pugi::xml_node child, const NamespaceScope& child_scope, const QName& name) {
                   if (ns::is_gml(name.uri)) return;
                   if (name.local == "connects") {
                     transition.state_ids.push_back(href_of(child, child_scope));
                   } else if (name.local == "duality") {
                     transition.boundary_id = href_of(child, child_scope);
                   } else if (name.local == "weight") {
                     const std::string_view text(child.child_value());
                     double weight = 0.0;
                     std::from_chars(text.data(), text.data() + text.size(), weight);
                     transition.weight = weight;
                   } else if (is_geometry_wrapper(name.local)) {
                     for (const auto& p : gml_.read_first_points(child, scope, 0))
                       transition.line.push_back(p);
                   }
                 });
    building_.transitions.push_back(std::move(transition));
  }

  const XmlSource& source_;
  maps::RawBuilding& building_;
  GmlReader gml_;
  bool direct_geometry_ = false;
  std::string layer_;  ///< gml:id of the SpaceLayer being walked
};

}  // namespace

maps::RawBuilding read_indoorgml_structure(const XmlSource& source) {
  const pugi::xml_node root = source.document().document_element();
  const NamespaceScope root_scope(nullptr, root);
  const QName root_name = root_scope.resolve_element(root.name());
  auto root_place = [&] {
    maps::SourcePlace place;
    place.line = source.line_of(root);
    place.element = std::string(root_name.local);
    if (const auto id = root_scope.attribute(root, ns::kGml, "id")) place.id = id.value();
    return maps::describe(place);
  };
  if (!root) throw InputError(source.path(), "line 1", "empty XML document");
  if (root_name.local != "IndoorFeatures" || !ns::is_indoorgml(root_name.uri)) {
    throw InputError(source.path(), root_place(),
                     "not an IndoorGML document: the root element must be IndoorFeatures in an "
                     "IndoorGML namespace, found \"" +
                         std::string(root.name()) + "\" in namespace \"" +
                         std::string(root_name.uri) + "\"");
  }

  maps::RawBuilding building;
  std::vector<std::string> duplicates;
  const IdIndex ids = index_gml_ids(source.document(), duplicates);
  for (const auto& id : duplicates) {
    building.warnings.push_back("duplicate gml:id \"" + id + "\" (xlinks use the first)");
  }
  StructureWalker walker(source, ids, building);
  const NamespaceScope outer_scope(nullptr, pugi::xml_node{});
  walker.walk(root, outer_scope);

  if (root_name.uri.find("/2.0") != std::string_view::npos) {
    building.version = "2.0";
  } else {
    building.version = walker.saw_direct_geometry() ? "1.0.1" : "1.0.3";
  }
  const bool any_geometry =
      std::any_of(building.cells.begin(), building.cells.end(),
                  [](const auto& c) { return !c.shells.empty() || !c.footprints_2d.empty(); });
  if (building.cells.empty() || !any_geometry) {
    throw InputError(source.path(), root_place(),
                     building.cells.empty() ? "empty model: no cellSpaceMember / CellSpace"
                                            : "empty model: no cell has any geometry");
  }
  return building;
}

}  // namespace conicloc::io
