#pragma once
// The IndoorGML structure walk: finds cells, boundaries, states and transitions in a parsed
// document (1.0.1, 1.0.3 and 2.0 layouts, core, navigation and extension classes) and reads their
// geometry into a RawBuilding. Elements are matched by namespace URI and local name.

#include "io/xml_source.hpp"
#include "maps/raw_building.hpp"

namespace conicloc::io {

/// Throws InputError (file, line, element, gml:id) for a document that is not IndoorGML, broken
/// xlinks, bad or missing coordinates, or a model without any cell geometry.
maps::RawBuilding read_indoorgml_structure(const XmlSource& source);

}  // namespace conicloc::io
