#include "eval/details_csv_reader.hpp"

#include <array>
#include <cmath>
#include <sstream>

#include "io/input_error.hpp"

namespace conicloc::eval {
namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

constexpr std::array<const char*, 12> kColumns = {
    "time_s", "x", "y", "z", "qx", "qy", "qz", "qw", "particles", "time_ms", "recovered", "status"};
enum Column { kTime, kX, kY, kZ, kQx, kQy, kQz, kQw, kParticles, kTimeMs, kRecovered, kStatus };

}  // namespace

std::vector<DetailsRow> read_details_csv(const std::string& text, const std::string& file) {
  std::stringstream lines(text);
  std::string line;
  if (!std::getline(lines, line)) throw io::InputError(file, "line 1", "empty file, no header");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const auto names = split_fields(line);
  std::array<std::size_t, kColumns.size()> column{};
  for (std::size_t c = 0; c < kColumns.size(); ++c) {
    std::size_t found = 0;
    while (found < names.size() && names[found] != kColumns[c]) ++found;
    if (found == names.size())
      throw io::InputError(file, "line 1", std::string("no column '") + kColumns[c] + "'");
    column[c] = found;
  }

  std::vector<DetailsRow> rows;
  for (std::size_t number = 2; std::getline(lines, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const auto fields = split_fields(line);
    const std::string place = "line " + std::to_string(number);
    if (fields.size() != names.size()) {
      throw io::InputError(file, place,
                           std::to_string(fields.size()) + " fields, the header has " +
                               std::to_string(names.size()));
    }
    const auto number_at = [&](Column c) {
      const std::string& field = fields[column[c]];
      try {
        std::size_t used = 0;
        const double value = std::stod(field, &used);
        if (used == field.size() && std::isfinite(value)) return value;
      } catch (const std::exception&) {
      }
      throw io::InputError(file, place,
                           std::string(kColumns[c]) + " '" + field + "' is not a finite number");
    };
    DetailsRow row;
    row.time_s = number_at(kTime);
    const Eigen::Quaterniond q(number_at(kQw), number_at(kQx), number_at(kQy), number_at(kQz));
    if (q.norm() < 0.5) throw io::InputError(file, place, "orientation quaternion is not unit");
    row.T_map_sensor = localizer::Pose3::Identity();
    row.T_map_sensor.linear() = q.normalized().toRotationMatrix();
    row.T_map_sensor.translation() << number_at(kX), number_at(kY), number_at(kZ);
    row.particles = number_at(kParticles);
    row.time_ms = number_at(kTimeMs);
    row.recovered = number_at(kRecovered) != 0.0;
    row.status = fields[column[kStatus]];
    rows.push_back(std::move(row));
  }
  return rows;
}

}  // namespace conicloc::eval
