#pragma once
// Escaping text for XML 1.0 documents we write (SVG floor plans, charts).

#include <string>

namespace conicloc::io {

/// `text` with & < > " ' as entities and the control characters XML 1.0 forbids dropped, so it
/// can go into element text and attribute values alike.
std::string escape_xml(const std::string& text);

}  // namespace conicloc::io
