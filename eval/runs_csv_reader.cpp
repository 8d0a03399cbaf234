#include "eval/runs_csv_reader.hpp"

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

#include "io/input_error.hpp"

namespace conicloc::eval {
namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

// One line's fields, read by column name, with the line's number for every error.
class Row {
 public:
  Row(const std::map<std::string, std::size_t>& columns, std::vector<std::string> fields,
      const std::string& file, int line)
      : columns_(columns), fields_(std::move(fields)), file_(file), line_(line) {}

  bool has(const std::string& column) const { return columns_.count(column) > 0; }

  std::string text(const std::string& column) const {
    const auto it = columns_.find(column);
    return it == columns_.end() ? std::string() : fields_[it->second];
  }

  double number(const std::string& column) const {
    const std::string value = text(column);
    if (value.empty()) return 0.0;
    double parsed = 0.0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), parsed);
    if (error != std::errc() || end != value.data() + value.size() || !std::isfinite(parsed))
      fail(column, value);
    return parsed;
  }

  std::optional<double> optional_number(const std::string& column) const {
    if (text(column).empty()) return std::nullopt;
    return number(column);
  }

  template <typename Integer>
  Integer whole(const std::string& column) const {
    const std::string value = text(column);
    if (value.empty()) return 0;
    Integer parsed = 0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), parsed);
    if (error != std::errc() || end != value.data() + value.size()) fail(column, value);
    return parsed;
  }

  int setting(const std::string& column) const {
    return text(column) == "default" ? kDefaultSetting : whole<int>(column);
  }

  ErrorStats stats(const std::string& rmse, const std::string& mean = "",
                   const std::string& median = "", const std::string& max = "") const {
    ErrorStats s;
    s.rmse = number(rmse);
    if (!mean.empty()) s.mean = number(mean);
    if (!median.empty()) s.median = number(median);
    if (!max.empty()) s.max = number(max);
    return s;
  }

 private:
  [[noreturn]] void fail(const std::string& column, const std::string& value) const {
    throw io::InputError(file_, "line " + std::to_string(line_),
                         "column " + column + ": '" + value + "' is not a number");
  }

  const std::map<std::string, std::size_t>& columns_;
  std::vector<std::string> fields_;
  const std::string& file_;
  int line_;
};

RunRecord record_of(const Row& row) {
  RunRecord r;
  r.model = row.text("model");
  r.particles = row.setting("particles");
  r.beams = row.setting("beams");
  r.seed = row.whole<std::uint64_t>("seed");
  r.scenario = row.text("scenario");
  r.building = row.text("building");
  auto& m = r.metrics;
  m.ate_xy_m = row.stats("ate_xy_rmse_m", "ate_xy_mean_m", "ate_xy_median_m", "ate_xy_max_m");
  m.ate_z_m = row.stats("ate_z_rmse_m");
  m.heading_deg = row.stats("heading_rmse_deg");
  m.heading_deg.max = row.number("heading_max_deg");
  m.rpe_trans_per_m = row.stats("rpe_trans_per_m");
  m.rpe_rot_deg_per_m = row.stats("rpe_rot_deg_per_m");
  m.convergence_time_s = row.optional_number("convergence_time_s");
  m.matched = row.whole<std::size_t>("matched");
  m.missing = row.whole<std::size_t>("missing");
  m.estimates = m.matched + m.missing;
  r.time_per_scan_ms = row.number("time_per_scan_ms");
  r.realtime_factor = row.number("realtime_factor");
  r.converged = row.text("converged") == "1";
  r.time_p95_ms = row.number("time_p95_ms");
  r.mean_particles = row.number("mean_particles");
  r.scans = row.whole<std::size_t>("scans");
  r.recoveries = row.whole<std::size_t>("recoveries");
  r.threads = row.whole<int>("threads");
  r.cores = row.whole<int>("cores");
  r.estimate_file = row.text("estimate");
  r.error = row.text("error");
  r.failed = !r.error.empty();
  r.building_group = row.text("building_group");
  r.odometry = !row.has("odometry") || row.text("odometry") == "1";
  r.capture_s = row.number("capture_s");
  r.false_alarms = row.whole<std::size_t>("false_alarms");
  r.time_to_10cm_s = row.optional_number("time_to_10cm_s");
  if (row.has("storeys")) {  // written since the cost-against-size columns came
    r.storeys = row.whole<int>("storeys");
    r.planes = row.whole<std::size_t>("planes");
    r.floor_area_m2 = row.number("floor_area_m2");
    r.start_time_ms = row.number("start_time_ms");
    r.search_scans = row.whole<std::size_t>("search_scans");
    r.search_time_mean_ms = row.number("search_time_mean_ms");
    r.search_time_max_ms = row.number("search_time_max_ms");
    r.tracking_time_mean_ms = row.number("tracking_time_mean_ms");
  }
  r.scored_at_50cm = row.has("time_to_50cm_s");
  r.time_to_50cm_s = row.optional_number("time_to_50cm_s");
  r.map_fit_xy_rmse_m = row.optional_number("map_fit_xy_rmse_m");
  r.ate_xy_rmse_to_map_fit_m = row.optional_number("ate_xy_rmse_to_map_fit_m");
  r.map_fit_heading_rmse_deg = row.optional_number("map_fit_heading_rmse_deg");
  r.heading_rmse_to_map_fit_deg = row.optional_number("heading_rmse_to_map_fit_deg");
  return r;
}

}  // namespace

RunsCsv read_runs_csv(const std::string& text, const std::string& file) {
  RunsCsv result;
  std::vector<std::string> lines;
  std::stringstream stream(text);
  std::string line;
  while (std::getline(stream, line)) lines.push_back(line);
  const bool cut_short = !text.empty() && text.back() != '\n';
  if (lines.empty() || (lines.size() == 1 && cut_short)) {
    result.dropped_partial_line = cut_short;
    return result;  // nothing written yet, or stopped while writing the header
  }
  const auto names = split_fields(lines.front());
  std::map<std::string, std::size_t> columns;
  for (std::size_t i = 0; i < names.size(); ++i) columns.emplace(names[i], i);
  for (const char* key : {"model", "particles", "beams", "seed", "scenario", "building"}) {
    if (!columns.count(key))
      throw io::InputError(file, "line 1", std::string("no column '") + key + "'");
  }
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const bool last = i + 1 == lines.size();
    auto fields = split_fields(lines[i]);
    if (last && (cut_short || fields.size() != names.size())) {
      result.dropped_partial_line = true;
      break;
    }
    if (fields.size() != names.size()) {
      throw io::InputError(file, "line " + std::to_string(i + 1),
                           "expected " + std::to_string(names.size()) + " fields, found " +
                               std::to_string(fields.size()));
    }
    result.runs.push_back(
        record_of(Row(columns, std::move(fields), file, static_cast<int>(i + 1))));
  }
  return result;
}

}  // namespace conicloc::eval
