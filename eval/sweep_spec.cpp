#include "eval/sweep_spec.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "eval/sweep_scenario.hpp"
#include "io/input_error.hpp"
#include "localizer/models/observation_factory.hpp"

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
  std::vector<Integer> integers(const std::vector<std::string>& items, double lo, double hi,
                                bool allow_default = false) const {
    std::vector<Integer> values;
    for (const auto& item : items) {
      if (allow_default && item == "default") {
        values.push_back(static_cast<Integer>(kDefaultSetting));
        continue;
      }
      const double value = number(item, lo, hi);
      if (value != std::floor(value)) fail("'" + item + "' is not a whole number");
      values.push_back(static_cast<Integer>(value));
    }
    return values;
  }

  void apply(const std::string& key, const std::vector<std::string>& items, SweepSpec& spec) const {
    if (key == "maps") spec.warnings.clear();  // they concern only the base's maps
    if (key == "maps" && items.empty()) {      // only --map
      spec.maps.clear();
      return;
    }
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
      spec.particles = integers<int>(items, 1, 1e6, true);
    } else if (key == "beams") {
      spec.beams = integers<int>(items, 0, 1e7, true);
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
        spec.maps.push_back(is_generated_map(map) || p.is_absolute()
                                ? map
                                : (folder / p).lexically_normal().string());
      }
    } else {
      fail("unknown key '" + key +
           "' (known: base, maps, models, particles, beams, seeds, scenarios, duration_s, "
           "threads, keep_captures)");
    }
  }

  SweepSpec parse(std::istream& in, const std::string& public_models_dir) {
    struct Line {
      int number;
      std::string key;
      std::vector<std::string> items;
    };
    std::vector<Line> lines;
    std::string text;
    while (std::getline(in, text)) {
      ++line_;
      text = trim(text.substr(0, text.find('#')));
      if (text.empty()) continue;
      const auto equals = text.find('=');
      if (equals == std::string::npos) fail("expected 'key = value, value, ...'");
      lines.push_back({line_, trim(text.substr(0, equals)), split_list(text.substr(equals + 1))});
    }
    // The base first, wherever it stands: every other key modifies it.
    SweepSpec spec = quick_sweep();
    for (const auto& line : lines) {
      if (line.key != "base") continue;
      line_ = line.number;
      if (line.items.size() != 1) fail("'base' takes one value: quick, full, robustness or scale");
      const std::string& base = line.items.front();
      if (base != "quick" && base != "full" && base != "robustness" && base != "scale")
        fail("unknown base '" + base + "' (known: quick, full, robustness, scale)");
      spec = resolve_sweep(base, public_models_dir);
    }
    spec.name = path_;
    for (const auto& line : lines) {
      if (line.key == "base") continue;
      line_ = line.number;
      apply(line.key, line.items, spec);
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
  spec.models = localizer::observation_model_names();
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
  spec.models = localizer::observation_model_names();
  spec.particles = {100, 300, 1000, 3000, 10000, 20000};
  spec.beams = {250, 1000, 2000};
  spec.seeds = {1, 2, 3};
  // The scenarios there were before the robustness corpus; that has its own sweep.
  spec.scenarios = {"robot", "handheld", "clean", "clutter", "map-error", "global", "kidnap"};
  spec.duration_s = 30.0;
  return spec;
}

SweepSpec robustness_sweep(const std::string& public_models_dir) {
  SweepSpec spec;
  spec.name = "robustness";
  namespace fs = std::filesystem;
  std::error_code error;
  if (!public_models_dir.empty() && fs::is_directory(public_models_dir, error)) {
    for (const auto& entry : fs::directory_iterator(public_models_dir, error)) {
      if (entry.path().extension() == ".gml") spec.maps.push_back(entry.path().string());
    }
    std::sort(spec.maps.begin(), spec.maps.end());
  } else {
    spec.warnings.push_back("no folder of public IndoorGML models at '" + public_models_dir +
                            "': the robustness sweep runs without them");
  }
  // Without a seed: a new building per sweep seed, so the corpus cannot be learnt by heart.
  for (const char* kind : {"corridor", "wings", "hall", "storeys"})
    spec.maps.push_back(std::string("generated:") + kind);
  spec.models = localizer::observation_model_names();
  spec.particles = {kDefaultSetting};
  spec.beams = {kDefaultSetting};
  spec.seeds = {1, 2, 3, 4, 5};
  spec.scenarios = {"robot",          "robot-no-odom", "handheld-no-odom",
                    "crowd",          "map-error-5cm", "global",
                    "global-no-odom", "kidnap",        "kidnap-no-odom"};
  spec.duration_s = 30.0;
  return spec;
}

SweepSpec scale_sweep() {
  SweepSpec spec;
  spec.name = "scale";
  for (const char* scale : {"1x1", "2x1", "5x1", "10x1", "1x2", "1x4", "10x4"})
    spec.maps.push_back(std::string("generated:storeys:1:") + scale);
  spec.models = {"conic-beam"};
  spec.particles = {kDefaultSetting};
  spec.beams = {kDefaultSetting};
  spec.seeds = {1, 2, 3, 4, 5};
  spec.scenarios = {"robot", "global"};
  spec.duration_s = 20.0;
  return spec;
}

SweepSpec read_sweep_file(const std::string& path, const std::string& public_models_dir) {
  std::ifstream in(path);
  if (!in) throw io::InputError(path, "", "cannot open the sweep file");
  return SweepFileParser(path).parse(in, public_models_dir);
}

SweepSpec resolve_sweep(const std::string& name_or_path, const std::string& public_models_dir) {
  if (name_or_path == "quick") return quick_sweep();
  if (name_or_path == "full") return full_sweep();
  if (name_or_path == "robustness") return robustness_sweep(public_models_dir);
  if (name_or_path == "scale") return scale_sweep();
  return read_sweep_file(name_or_path, public_models_dir);
}

std::string sweep_file_text(const SweepSpec& spec) {
  const auto join = [](const auto& values, const auto& text) {
    std::string joined;
    for (const auto& value : values) joined += (joined.empty() ? "" : ", ") + text(value);
    return joined;
  };
  const auto same = [](const std::string& s) { return s; };
  const auto number = [](auto value) { return std::to_string(value); };
  std::ostringstream out;
  out << "# A conicloc evaluation sweep, every key written out (conicloc evaluate --sweep FILE)\n";
  out << "maps = " << join(spec.maps, same) << "\n";
  out << "models = " << join(spec.models, same) << "\n";
  out << "particles = " << join(spec.particles, setting_text) << "\n";
  out << "beams = " << join(spec.beams, setting_text) << "\n";
  out << "seeds = " << join(spec.seeds, number) << "\n";
  out << "scenarios = " << join(spec.scenarios, same) << "\n";
  out.precision(17);
  out << "duration_s = " << spec.duration_s << "\n";
  out << "threads = " << spec.threads << "\n";
  out << "keep_captures = " << (spec.keep_captures ? "true" : "false") << "\n";
  return out.str();
}

bool is_generated_map(const std::string& map) {
  return map.rfind("generated:", 0) == 0;
}

std::string setting_text(int value) {
  return value == kDefaultSetting ? std::string("default") : std::to_string(value);
}

std::string beams_text(int beams) {
  return beams == 0 ? std::string("all") : setting_text(beams);
}

}  // namespace conicloc::eval
