#include "io/input_error.hpp"

namespace conicloc::io {

InputError::InputError(const std::string& file, const std::string& place, const std::string& what)
    : std::runtime_error(file + (place.empty() ? "" : ": " + place) + ": " + what),
      file_(file),
      place_(place) {}

}  // namespace conicloc::io
