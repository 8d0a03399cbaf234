#include "io/xml_source.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "io/input_error.hpp"

namespace conicloc::io {
namespace {

// The loaders walk the element tree recursively; real IndoorGML nests ~20 levels. A bound keeps a
// hostile file (100k nested tags) from overflowing the stack.
constexpr int kMaxElementDepth = 256;

std::string hex_byte(unsigned char c) {
  char text[8];
  std::snprintf(text, sizeof text, "0x%02x", c);
  return text;
}

// Looks at the first bytes before reading the whole file, so a large file that is not XML (a
// capture, a gigabyte of garbage) is refused at once instead of being read into memory.
void sniff_xml(std::ifstream& stream, const std::string& path) {
  char head[512];
  stream.read(head, sizeof head);
  const auto count = static_cast<std::size_t>(stream.gcount());
  if (stream.bad()) throw InputError(path, "", "read error");
  stream.clear();
  stream.seekg(0);
  if (count == 0) throw InputError(path, "", "empty file");
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(head[i]); };
  // UTF-16/32 byte order marks or a NUL next to '<' : pugixml detects those encodings itself.
  if (count >= 2 && ((byte(0) == 0xFE && byte(1) == 0xFF) || (byte(0) == 0xFF && byte(1) == 0xFE)))
    return;
  if (count >= 2 && ((byte(0) == 0 && byte(1) == '<') || (byte(0) == '<' && byte(1) == 0))) return;
  std::size_t i = 0;
  if (count >= 3 && byte(0) == 0xEF && byte(1) == 0xBB && byte(2) == 0xBF) i = 3;  // UTF-8 BOM
  while (i < count && (head[i] == ' ' || head[i] == '\t' || head[i] == '\r' || head[i] == '\n'))
    ++i;
  if (i == count) {
    if (count < sizeof head) throw InputError(path, "", "file holds only white space");
    return;  // 512 blanks: let the parser judge
  }
  if (head[i] != '<') {
    throw InputError(path, "byte offset " + std::to_string(i),
                     "not an XML file: starts with " + hex_byte(byte(i)) + " instead of '<'");
  }
}

// Deepest element, found without recursion (document order: child, sibling, or up and over).
void check_depth(const XmlSource& source, const pugi::xml_document& document) {
  int depth = 0;
  pugi::xml_node node = document.first_child();
  while (node) {
    if (node.type() == pugi::node_element && depth + 1 > kMaxElementDepth) {
      throw InputError(
          source.path(),
          "line " + std::to_string(source.line_of(node)) + ", element " + node.name(),
          "elements nested more than " + std::to_string(kMaxElementDepth) + " levels deep");
    }
    if (node.first_child()) {
      node = node.first_child();
      ++depth;
      continue;
    }
    while (node && !node.next_sibling()) {
      node = node.parent();
      --depth;
      if (node == document) return;
    }
    if (node) node = node.next_sibling();
  }
}

}  // namespace

XmlSource::XmlSource(const std::string& path) : path_(path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    throw InputError(path, "", "is a directory, not an XML file");
  }
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw InputError(path, "", "cannot open file");
  sniff_xml(stream, path);
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
  check_depth(*this, document_);
}

int XmlSource::line_of_offset(std::ptrdiff_t offset) const {
  if (offset < 0) return 0;
  const auto it = std::lower_bound(newline_offsets_.begin(), newline_offsets_.end(), offset);
  return static_cast<int>(it - newline_offsets_.begin()) + 1;
}

}  // namespace conicloc::io
