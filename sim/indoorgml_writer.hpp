#pragma once
// A PrismBuilding as an IndoorGML 1.0.3 document, encoded as scripts/make_example_building.py
// encodes the example building (see its docstring): every cell a gml:Solid with an outward shell
// (pillars as interior shells), every door a navi:ConnectionBoundary dual to a core:Transition
// between the two cells' States, States 0.5 m above the floor, closed rings in gml:posList
// srsDimension="3", no CRS. Deterministic: the same building gives the same bytes.

#include <string>

#include "sim/prism_building.hpp"

namespace conicloc::sim {

std::string write_indoorgml(const PrismBuilding& building);

}  // namespace conicloc::sim
