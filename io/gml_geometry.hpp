#pragma once
// GML 3.2 geometry as IndoorGML uses it: Solid (exterior and interior shells), Shell,
// CompositeSurface, MultiSurface, Polygon with interior rings, OrientableSurface (orientation "-"),
// xlink:href to polygons, gml:pos / gml:posList / gml:coordinates with srsDimension 2, 3 or missing
// (inherited from ancestors, else inferred from the counts), LineString and Point.

#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/xml_namespace_scope.hpp"
#include "io/xml_source.hpp"
#include "maps/raw_building.hpp"

namespace conicloc::io {

/// gml:id -> element, for xlink:href resolution.
using IdIndex = std::unordered_map<std::string_view, pugi::xml_node>;

/// Every element of the document with a gml:id. Duplicated ids are appended to `duplicates`.
IdIndex index_gml_ids(const pugi::xml_document& document, std::vector<std::string>& duplicates);

class GmlReader {
 public:
  GmlReader(const XmlSource& source, const IdIndex& ids, maps::RawBuilding& building)
      : source_(source), ids_(ids), building_(building) {}

  /// Shells of a Solid / CompositeSolid / MultiSolid, or one shell holding the polygons of any
  /// surface geometry (Shell, CompositeSurface, MultiSurface, Polygon, OrientableSurface).
  std::vector<maps::RawShell> read_shells(pugi::xml_node geometry, const NamespaceScope& scope,
                                          int srs_dimension);

  /// Polygons of any surface geometry, orientation "-" applied.
  void read_surfaces(pugi::xml_node geometry, const NamespaceScope& scope, int srs_dimension,
                     bool reversed, std::vector<maps::RawPolygon>& out);

  /// Points of a LinearRing, LineString, Point (pos, posList, coordinates or pointProperty).
  maps::Ring3 read_points(pugi::xml_node geometry, const NamespaceScope& scope, int srs_dimension);

  /// First LineString / Point / any geometry's points found below `node`, empty if none.
  maps::Ring3 read_first_points(pugi::xml_node node, const NamespaceScope& scope,
                                int srs_dimension);

  /// "line L, element <local> (gml:id=...)" with the nearest gml:id at or above `node`.
  maps::SourcePlace place(pugi::xml_node node, const NamespaceScope& scope) const;
  [[noreturn]] void fail(pugi::xml_node node, const NamespaceScope& scope,
                         const std::string& what) const;

  /// srsDimension of `node` if it states one, else `inherited`; records the first srsName.
  int dimension_at(pugi::xml_node node, int inherited);

 private:
  void read_polygon(pugi::xml_node polygon, const NamespaceScope& scope, int srs_dimension,
                    bool reversed, std::vector<maps::RawPolygon>& out);
  void follow_href(pugi::xml_node reference, const NamespaceScope& scope, int srs_dimension,
                   bool reversed, std::vector<maps::RawPolygon>& out);
  void parse_numbers(pugi::xml_node element, const NamespaceScope& scope, std::string_view text,
                     std::vector<double>& values) const;

  const XmlSource& source_;
  const IdIndex& ids_;
  maps::RawBuilding& building_;
  int href_depth_ = 0;  // guards against xlink cycles
};

}  // namespace conicloc::io
