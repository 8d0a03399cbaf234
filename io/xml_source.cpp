#include "io/xml_source.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>

#include "io/input_error.hpp"

namespace conicloc::io {

XmlSource::XmlSource(const std::string& path) : path_(path) {
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw InputError(path, "", "cannot open file");
  std::string bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  if (stream.bad()) throw InputError(path, "", "read error");
  size_bytes_ = bytes.size();
  for (std::size_t i = bytes.find('\n'); i != std::string::npos; i = bytes.find('\n', i + 1)) {
    newline_offsets_.push_back(static_cast<std::ptrdiff_t>(i));
  }
  // parse_default keeps offsets valid for offset_debug(); no whitespace-only PCDATA nodes.
  const pugi::xml_parse_result result =
      document_.load_buffer(bytes.data(), bytes.size(), pugi::parse_default, pugi::encoding_auto);
  if (!result) {
    std::ostringstream place;
    place << "line " << line_of_offset(result.offset);
    throw InputError(path, place.str(), std::string("malformed XML: ") + result.description());
  }
}

int XmlSource::line_of_offset(std::ptrdiff_t offset) const {
  if (offset < 0) return 0;
  const auto it = std::lower_bound(newline_offsets_.begin(), newline_offsets_.end(), offset);
  return static_cast<int>(it - newline_offsets_.begin()) + 1;
}

}  // namespace conicloc::io
