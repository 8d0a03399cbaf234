#include "maps/raw_building.hpp"

namespace conicloc::maps {

std::string describe(const SourcePlace& place) {
  std::string out = "line " + std::to_string(place.line) + ", element " + place.element;
  if (!place.id.empty()) out += " (gml:id=\"" + place.id + "\")";
  return out;
}

}  // namespace conicloc::maps
