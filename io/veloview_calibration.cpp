#include "io/veloview_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <pugixml.hpp>

#include "io/input_error.hpp"
#include "io/velodyne_packet.hpp"
#include "sensor/builtin_calibration.hpp"

namespace conicloc::io {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

std::string place_of(const pugi::xml_node& node, const std::string& what) {
  return "element " + what + " (byte offset " + std::to_string(node.offset_debug()) + ")";
}

double number(const std::string& path, const pugi::xml_node& parent, const char* name,
              double fallback, bool required) {
  const pugi::xml_node child = parent.child(name);
  if (!child) {
    if (required)
      throw InputError(path, place_of(parent, parent.name()),
                       std::string("missing <") + name + ">");
    return fallback;
  }
  const std::string text = child.text().as_string();
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  while (end && *end == ' ') ++end;
  if (text.empty() || !end || *end != '\0' || !std::isfinite(value)) {
    throw InputError(path, place_of(child, name), "not a number: \"" + text + "\"");
  }
  return value;
}

}  // namespace

LoadedCalibration read_veloview_calibration(const std::string& path, sensor::SensorModel model) {
  pugi::xml_document document;
  const pugi::xml_parse_result parsed = document.load_file(path.c_str());
  if (!parsed) {
    throw InputError(path, "byte offset " + std::to_string(parsed.offset),
                     std::string("cannot read calibration XML: ") + parsed.description());
  }
  const pugi::xml_node db = document.child("boost_serialization").child("DB");
  if (!db)
    throw InputError(path, "root", "no <boost_serialization><DB>: not a VeloView calibration");
  const pugi::xml_node points = db.child("points_");
  if (!points) throw InputError(path, place_of(db, "DB"), "missing <points_>");

  const int channels = velodyne::packet_layout(model).channels;
  LoadedCalibration loaded;
  loaded.calibration = sensor::builtin_calibration(model);  // keeps ring ranking helpers' layout
  loaded.distance_unit_m = number(path, db, "distLSB_", 0.2, false) * 0.01;
  std::vector<bool> seen(static_cast<std::size_t>(channels), false);
  bool unmodelled = false;
  for (const pugi::xml_node item : points.children("item")) {
    const pugi::xml_node px = item.child("px");
    if (!px) continue;
    const double id = number(path, px, "id_", 0, true);
    if (id < 0 || id != std::floor(id)) throw InputError(path, place_of(px, "px"), "bad laser id");
    if (id >= channels) continue;  // VeloView lists 64 lasers; the model fires fewer
    const auto k = static_cast<std::size_t>(id);
    auto& laser = loaded.calibration.lasers[k];
    laser.elevation_rad = number(path, px, "vertCorrection_", 0, true) * kDegToRad;
    laser.azimuth_offset_rad = number(path, px, "rotCorrection_", 0, false) * kDegToRad;
    laser.vertical_offset_m = number(path, px, "vertOffsetCorrection_", 0, false) * 0.01;
    laser.range_offset_m = number(path, px, "distCorrection_", 0, false) * 0.01;
    for (const char* name : {"distCorrectionX_", "distCorrectionY_", "horizOffsetCorrection_",
                             "focalDistance_", "focalSlope_"}) {
      unmodelled = unmodelled || number(path, px, name, 0, false) != 0.0;
    }
    seen[k] = true;
  }
  for (int k = 0; k < channels; ++k) {
    if (!seen[static_cast<std::size_t>(k)]) {
      throw InputError(path, place_of(points, "points_"),
                       "no laser with id_ " + std::to_string(k) + " (the " +
                           sensor::sensor_model_name(model) + " has " + std::to_string(channels) +
                           ")");
    }
  }
  // Re-rank rings by the file's elevations.
  std::vector<int> order(static_cast<std::size_t>(channels));
  for (int k = 0; k < channels; ++k) order[static_cast<std::size_t>(k)] = k;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return loaded.calibration.lasers[a].elevation_rad < loaded.calibration.lasers[b].elevation_rad;
  });
  for (int rank = 0; rank < channels; ++rank) loaded.calibration.lasers[order[rank]].ring = rank;
  if (unmodelled) {
    loaded.warnings.push_back(
        path +
        ": two-point distance, horizontal-offset or focal corrections are not "
        "modelled and were ignored");
  }
  if (std::abs(loaded.distance_unit_m - velodyne::packet_layout(model).distance_unit_m) > 1e-9) {
    loaded.warnings.push_back(path + ": distLSB_ " + std::to_string(loaded.distance_unit_m * 100) +
                              " cm differs from the model's distance unit; the model's is used");
  }
  return loaded;
}

void write_veloview_calibration(const std::string& path,
                                const sensor::LaserCalibration& calibration,
                                double distance_unit_m) {
  std::ofstream out(path);
  out << std::setprecision(17);  // max_digits10: a double reads back to the same bits
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\" standalone=\"yes\" ?>\n"
      << "<!DOCTYPE boost_serialization>\n"
      << "<boost_serialization signature=\"serialization::archive\" version=\"4\">\n"
      << "<DB class_id=\"0\" tracking_level=\"0\" version=\"0\">\n"
      << "  <distLSB_>" << distance_unit_m * 100.0 << "</distLSB_>\n"
      << "  <points_ class_id=\"1\" tracking_level=\"0\" version=\"0\">\n"
      << "    <count>" << calibration.lasers.size() << "</count>\n"
      << "    <item_version>1</item_version>\n";
  for (std::size_t k = 0; k < calibration.lasers.size(); ++k) {
    const sensor::Laser& laser = calibration.lasers[k];
    out << "    <item class_id=\"2\" tracking_level=\"0\" version=\"1\">\n"
        << "      <px class_id=\"3\" tracking_level=\"1\" version=\"1\" object_id=\"_" << k
        << "\">\n"
        << "        <id_>" << k << "</id_>\n"
        << "        <rotCorrection_>" << laser.azimuth_offset_rad / kDegToRad
        << "</rotCorrection_>\n"
        << "        <vertCorrection_>" << laser.elevation_rad / kDegToRad << "</vertCorrection_>\n"
        << "        <distCorrection_>" << laser.range_offset_m * 100.0 << "</distCorrection_>\n"
        << "        <distCorrectionX_>0</distCorrectionX_>\n"
        << "        <distCorrectionY_>0</distCorrectionY_>\n"
        << "        <vertOffsetCorrection_>" << laser.vertical_offset_m * 100.0
        << "</vertOffsetCorrection_>\n"
        << "        <horizOffsetCorrection_>0</horizOffsetCorrection_>\n"
        << "        <focalDistance_>0</focalDistance_>\n"
        << "        <focalSlope_>0</focalSlope_>\n"
        << "      </px>\n"
        << "    </item>\n";
  }
  out << "  </points_>\n</DB>\n</boost_serialization>\n";
  if (!out) throw InputError(path, "", "cannot write the calibration XML");
}

}  // namespace conicloc::io
