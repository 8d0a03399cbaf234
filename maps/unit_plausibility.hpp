#pragma once
// check_units(): whether a loaded building's sizes are those of a building in metres, and if not,
// which --unit-scale would make them so. A model in millimetres read as metres has 3000 m rooms.

#include <optional>
#include <string>

#include "maps/plane_map.hpp"

namespace conicloc::maps {

/// Plausible building sizes, metres.
struct UnitLimits {
  double min_storey_height_m = 1.8;   ///< floor to ceiling of a typical room
  double max_storey_height_m = 12.0;  ///< halls and atria stay below this
  double max_extent_m = 2000.0;       ///< the largest horizontal side of a building
};

struct UnitCheck {
  bool plausible = true;
  double storey_height_m = 0.0;  ///< median cell height (floor to ceiling), m; 0 if none
  double extent_m = 0.0;         ///< largest horizontal side of the bounding box, m
  std::string problem;           ///< what is implausible ("" when plausible)
  /// The --unit-scale (file units to metres) that makes the sizes plausible: 0.001 (mm), 0.01
  /// (cm), 0.0254 (inch), 0.3048 (feet) or 1; unset when none of them does.
  std::optional<double> suggested_unit_scale;
};

/// `unit_scale` is the scale the map was built with. `measure_height` is false for a 2D-only
/// model (its heights are the --storey-height given, not the file's), which is then judged by its
/// extent only.
UnitCheck check_units(const PlaneMap& map, double unit_scale, bool measure_height,
                      const UnitLimits& limits = {});

}  // namespace conicloc::maps
