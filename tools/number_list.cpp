#include "tools/number_list.hpp"

#include <CLI/CLI.hpp>
#include <cmath>
#include <sstream>

namespace conicloc::tools {

std::vector<double> parse_numbers(const std::string& text, std::size_t count,
                                  const std::string& flag) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    try {
      std::size_t used = 0;
      values.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(values.back())) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw CLI::ValidationError(flag, "'" + item + "' is not a number");
    }
  }
  if (values.size() != count) {
    throw CLI::ValidationError(
        flag, "expected " + std::to_string(count) + " comma-separated numbers, got '" + text + "'");
  }
  return values;
}

}  // namespace conicloc::tools
