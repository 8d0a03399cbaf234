#pragma once
// RawBuilding: an IndoorGML model as read from the file, before any geometry processing.
// io/ fills it (XML, namespaces, xlinks); maps/build_plane_map turns it into a PlaneMap. File
// coordinates as written (no CRS conversion, no origin shift, no unit scale), rings as written
// except that OrientableSurface orientation="-" is already applied (rings reversed).

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "maps/planar_polygon.hpp"

namespace conicloc::maps {

/// Where a raw item came from, for messages: "line 42, element Polygon (gml:id=\"P1\")".
struct SourcePlace {
  int line = 0;
  std::string element;  ///< local name
  std::string id;       ///< gml:id, may be empty
};

std::string describe(const SourcePlace& place);

struct RawPolygon {
  Ring3 outer;
  std::vector<Ring3> holes;
  std::string id;  ///< gml:id of the polygon, else of the closest ancestor with one
  SourcePlace place;
};

/// The surfaces bounding one solid shell (exterior or interior).
struct RawShell {
  std::vector<RawPolygon> polygons;
  bool interior = false;  ///< an interior shell (a void) of a gml:Solid
};

struct RawCell {
  std::string id;
  std::string name;
  std::string class_name;     ///< local name: CellSpace, GeneralSpace, NonNavigableSpace, ...
  std::string namespace_uri;  ///< of the class element
  bool navigable = true;
  std::vector<RawShell> shells;           ///< 3D geometry (Solid shells, or a surface set)
  std::vector<RawPolygon> footprints_2d;  ///< 2D geometry (Geometry2D polygons)
  std::vector<std::string> boundary_ids;  ///< partialboundedBy references
  std::string state_id;                   ///< duality reference, may be empty
  std::string layer;  ///< the layer it is written in (2.0), empty when outside any (1.0)
  SourcePlace place;
};

struct RawBoundary {
  std::string id;
  std::string class_name;
  std::vector<RawPolygon> polygons;  ///< 3D boundary surfaces
  std::vector<Ring3> lines;          ///< 2D boundaries (LineStrings)
  std::string transition_id;         ///< duality reference, may be empty
  SourcePlace place;
};

struct RawState {
  std::string id;
  std::string class_name;
  std::string cell_id;  ///< duality reference, may be empty
  std::string layer;    ///< gml:id of the SpaceLayer that holds it, empty outside any
  std::optional<Eigen::Vector3d> point;
  SourcePlace place;
};

struct RawTransition {
  std::string id;
  std::vector<std::string> state_ids;  ///< connects (normally two)
  std::string boundary_id;             ///< duality reference, may be empty
  std::vector<Eigen::Vector3d> line;
  double weight = 0.0;
  SourcePlace place;
};

/// A SpaceLayer of the multi-layered graph (IndoorGML 1.0 core 7.2) or a ThematicLayer (2.0): a
/// partition of the building into cells of one kind, which its `class` (1.0: TOPOGRAPHIC, SENSOR,
/// LOGICAL, TAGS, UNKNOWN) or `theme` (2.0: Physical, Virtual, Unknown, Other) says.
struct RawLayer {
  std::string id;           ///< gml:id, else where it was read
  std::string layer_class;  ///< the class or theme element's text as written, empty when absent
  SourcePlace place;
};

struct RawBuilding {
  std::string version;  ///< "1.0.1", "1.0.3", "2.0"
  std::string crs;      ///< first srsName found, empty if none
  std::vector<RawCell> cells;
  std::vector<RawBoundary> boundaries;
  std::vector<RawState> states;
  std::vector<RawTransition> transitions;
  std::vector<RawLayer> layers;  ///< in file order
  int polygons_read = 0;
  std::map<std::string, int> polygons_dropped;  ///< reason -> count, dropped while parsing
  std::vector<std::string> warnings;
};

}  // namespace conicloc::maps
