#include "eval/sweep_spec.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "eval/sweep_scenario.hpp"
#include "io/input_error.hpp"
#include "localizer/observation_factory.hpp"

namespace conicloc::eval {
namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split_list(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    item = trim(item);
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

// Reads sweep-file lines, with the file and line number for every error.
class SweepFileParser {
 public:
  explicit SweepFileParser(std::string path) : path_(std::move(path)) {}

  [[noreturn]] void fail(const std::string& message) const {
    throw io::InputError(path_, "line " + std::to_string(line_), message);
  }

  double number(const std::string& text, double lo, double hi) const {
    try {
      std::size_t used = 0;
      const double value = std::stod(text, &used);
      if (used == text.size() && std::isfinite(value) && value >= lo && value <= hi) return value;
    } catch (const std::exception&) {
    }
    std::ostringstream message;
    message << "'" << text << "' is not a number in [" << lo << ", " << hi << "]";
    fail(message.str());
  }

  template <typename Integer>
  std::vector<Integer> integers(const std::vector<std::string>& items, double lo, double hi) const {
    std::vector<Integer> values;
    for (const auto& item : items) {
      const double value = number(item, lo, hi);
      if (value != std::floor(value)) fail("'" + item + "' is not a whole number");
      values.push_back(static_cast<Integer>(value));
    }
    return values;
  }

  void apply(const std::string& key, const std::vector<std::string>& items, SweepSpec& spec) const {
    if (items.empty()) fail("'" + key + "' has no values");
    const auto single = [&] {
      if (items.size() != 1) fail("'" + key + "' takes one value");
      return items.front();
    };
    if (key == "models") {
      const auto known = localizer::observation_model_names();
      for (const auto& model : items) {
        if (std::find(known.begin(), known.end(), model) == known.end())
          fail("unknown model '" + model + "'");
      }
      spec.models = items;
    } else if (key == "scenarios") {
      for (const auto& scenario : items) {
        if (!find_scenario(scenario)) fail("unknown scenario '" + scenario + "'");
      }
      spec.scenarios = items;
    } else if (key == "particles") {
      spec.particles = integers<int>(items, 1, 1e6);
    } else if (key == "beams") {
      spec.beams = integers<int>(items, 0, 1e7);
    } else if (key == "seeds") {
      spec.seeds = integers<std::uint64_t>(items, 0, 9.0e15);
    } else if (key == "duration_s") {
      spec.duration_s = number(single(), 1.0, 86400.0);
    } else if (key == "threads") {
      spec.threads = static_cast<int>(integers<int>({single()}, 0, 1024).front());
    } else if (key == "keep_captures") {
      const std::string value = single();
      if (value != "true" && value != "false") fail("keep_captures is true or false");
      spec.keep_captures = value == "true";
    } else if (key == "maps") {
      const auto folder = std::filesystem::path(path_).parent_path();
      spec.maps.clear();
      for (const auto& map : items) {
        const std::filesystem::path p(map);
        spec.maps.push_back(p.is_absolute() ? p.string() : (folder / p).lexically_normal().string());
      }
    } else {
      fail("unknown key '" + key +
           "' (known: maps, models, particles, beams, seeds, scenarios, duration_s, threads, "
           "keep_captures)");
    }
  }

  SweepSpec parse(std::istream& in) {
    SweepSpec spec = quick_sweep();
    spec.name = path_;
    std::string text;
    while (std::getline(in, text)) {
      ++line_;
      text = trim(text.substr(0, text.find('#')));
      if (text.empty()) continue;
      const auto equals = text.find('=');
      if (equals == std::string::npos) fail("expected 'key = value, value, ...'");
      apply(trim(text.substr(0, equals)), split_list(text.substr(equals + 1)), spec);
    }
    return spec;
  }

 private:
  std::string path_;
  int line_ = 0;
};

}  // namespace

SweepSpec quick_sweep() {
  SweepSpec spec;
  spec.name = "quick";
  spec.models = {"conic-beam", "conic-segment", "point-to-plane"};
  spec.particles = {300, 1000};
  spec.beams = {300, 1000};
  spec.seeds = {1};
  spec.scenarios = {"robot", "handheld"};
  spec.duration_s = 10.0;
  return spec;
}

SweepSpec full_sweep() {
  SweepSpec spec;
  spec.name = "full";
  spec.models = {"conic-beam", "conic-segment", "point-to-plane"};
  spec.particles = {100, 300, 1000, 3000, 10000, 20000};
  spec.beams = {250, 1000, 2000};
  spec.seeds = {1, 2, 3};
  spec.scenarios = scenario_names();
  spec.duration_s = 30.0;
  return spec;
}

SweepSpec read_sweep_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw io::InputError(path, "", "cannot open the sweep file");
  return SweepFileParser(path).parse(in);
}

SweepSpec resolve_sweep(const std::string& name_or_path) {
  if (name_or_path == "quick") return quick_sweep();
  if (name_or_path == "full") return full_sweep();
  return read_sweep_file(name_or_path);
}

}  // namespace conicloc::eval
