#pragma once
// The typed error of io/: every bad input names the file and the place (line, element, packet).

#include <stdexcept>
#include <string>

namespace conicloc::io {

class InputError : public std::runtime_error {
 public:
  /// `place` says where in the file: "line 42, element gml:Polygon (gml:id=\"P1\")", "packet 17".
  InputError(const std::string& file, const std::string& place, const std::string& what);

  const std::string& file() const { return file_; }
  const std::string& place() const { return place_; }

 private:
  std::string file_;
  std::string place_;
};

}  // namespace conicloc::io
