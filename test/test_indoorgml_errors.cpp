// Bad IndoorGML input: a typed error naming the file, the element (with its gml:id) and the line.
#include <gtest/gtest.h>

#include "io/indoorgml.hpp"
#include "io/input_error.hpp"

namespace {

std::string test_file(const std::string& name) {
  return std::string(CONICLOC_TEST_DATA) + "/indoorgml/" + name;
}

// Loads `name`, expects InputError whose message holds every one of `parts`.
void expect_error(const std::string& name, const std::vector<std::string>& parts) {
  try {
    conicloc::io::load_indoorgml(test_file(name));
    FAIL() << name << " loaded without error";
  } catch (const conicloc::io::InputError& error) {
    const std::string message = error.what();
    EXPECT_EQ(error.file(), test_file(name));
    EXPECT_NE(message.find(name), std::string::npos) << message;
    for (const auto& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

TEST(IndoorGmlErrors, MalformedXmlNamesLine) {
  expect_error("bad_malformed.gml", {"line 51", "malformed XML"});
}

TEST(IndoorGmlErrors, NotIndoorGml) {
  expect_error("bad_not_indoorgml.gml",
               {"line 2", "element CityModel", "gml:id=\"CM\"", "not an IndoorGML document"});
}

TEST(IndoorGmlErrors, BrokenXlink) {
  expect_error("bad_broken_xlink.gml",
               {"line 121", "element surfaceMember", "gml:id=\"SB\"", "#NO-SUCH-POLYGON"});
}

TEST(IndoorGmlErrors, NanCoordinate) {
  expect_error("bad_nan_coordinate.gml",
               {"line 10", "element pos", "gml:id=\"R1-ceil\"", "not a finite number"});
}

TEST(IndoorGmlErrors, MissingCoordinate) {
  expect_error("bad_missing_coordinate.gml",
               {"line 10", "element pos", "gml:id=\"R1-ceil\"", "missing coordinates"});
}

TEST(IndoorGmlErrors, EmptyModel) {
  expect_error("bad_empty_model.gml",
               {"line 2", "element IndoorFeatures", "gml:id=\"EMPTY\"", "empty model"});
}

TEST(IndoorGmlErrors, MissingFile) {
  EXPECT_THROW(conicloc::io::load_indoorgml(test_file("no_such_file.gml")),
               conicloc::io::InputError);
}

}  // namespace
