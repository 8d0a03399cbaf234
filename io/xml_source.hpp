#pragma once
// An XML file loaded with pugixml, with the byte-offset -> line table that error messages need
// (pugixml reports byte offsets, node.offset_debug(); lines are counted once, up front).

#include <pugixml.hpp>
#include <string>
#include <vector>

namespace conicloc::io {

class XmlSource {
 public:
  /// Reads and parses `path`. Throws InputError naming the file and line on I/O or XML errors.
  explicit XmlSource(const std::string& path);

  const std::string& path() const { return path_; }
  const pugi::xml_document& document() const { return document_; }
  std::size_t size_bytes() const { return size_bytes_; }

  /// 1-based line of a byte offset into the file.
  int line_of_offset(std::ptrdiff_t offset) const;
  int line_of(pugi::xml_node node) const { return line_of_offset(node.offset_debug()); }

 private:
  std::string path_;
  std::vector<std::ptrdiff_t> newline_offsets_;  // ascending offsets of every '\n'
  pugi::xml_document document_;
  std::size_t size_bytes_ = 0;
};

}  // namespace conicloc::io
