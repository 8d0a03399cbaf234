#pragma once
// A tiny streaming JSON writer (no JSON library on the system): objects, arrays, strings with
// escaping, numbers (non-finite -> null), booleans, null. Commas and nesting are tracked for you:
//   JsonWriter json(std::cout);
//   json.begin_object(); json.key("planes").value(42); json.key("bbox").array({0.0, 1.0});
//   json.end_object();

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <initializer_list>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace conicloc::tools {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out) : out_(out) {}

  JsonWriter& begin_object() {
    open('{');
    return *this;
  }
  JsonWriter& end_object() {
    close('}');
    return *this;
  }
  JsonWriter& begin_array() {
    open('[');
    return *this;
  }
  JsonWriter& end_array() {
    close(']');
    return *this;
  }

  /// Object key; the next call writes its value.
  JsonWriter& key(std::string_view name) {
    separate();
    write_string(name);
    out_ << ':';
    after_key_ = true;
    return *this;
  }

  JsonWriter& value(std::string_view text) {
    separate();
    write_string(text);
    return *this;
  }
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  JsonWriter& value(const std::string& text) { return value(std::string_view(text)); }
  JsonWriter& value(bool flag) {
    separate();
    out_ << (flag ? "true" : "false");
    return *this;
  }
  JsonWriter& value(double number) {
    separate();
    if (!std::isfinite(number)) {
      out_ << "null";
    } else {
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.17g", number);
      // Shortest text that reads back exactly, tried from 15 digits up.
      for (int digits = 15; digits < 17; ++digits) {
        char shorter[32];
        std::snprintf(shorter, sizeof shorter, "%.*g", digits, number);
        // strtod, not stod: stod throws on a subnormal (ERANGE), which reads back exactly.
        if (std::strtod(shorter, nullptr) == number) {
          out_ << shorter;
          return *this;
        }
      }
      out_ << buffer;
    }
    return *this;
  }
  JsonWriter& value(int number) {
    separate();
    out_ << number;
    return *this;
  }
  JsonWriter& value(long number) {
    separate();
    out_ << number;
    return *this;
  }
  JsonWriter& value(long long number) {
    separate();
    out_ << number;
    return *this;
  }
  JsonWriter& value(unsigned long number) {
    separate();
    out_ << number;
    return *this;
  }
  JsonWriter& null() {
    separate();
    out_ << "null";
    return *this;
  }

  /// An array of numbers in one call.
  JsonWriter& array(std::initializer_list<double> numbers) {
    begin_array();
    for (const double number : numbers) value(number);
    return end_array();
  }
  template <typename Container>
  JsonWriter& array_of(const Container& values) {
    begin_array();
    for (const auto& item : values) value(item);
    return end_array();
  }

 private:
  void separate() {
    if (after_key_) {
      after_key_ = false;
      return;
    }
    if (!first_.empty()) {
      if (!first_.back()) out_ << ',';
      first_.back() = false;
    }
  }
  void open(char bracket) {
    separate();
    out_ << bracket;
    first_.push_back(true);
  }
  void close(char bracket) {
    if (!first_.empty()) first_.pop_back();
    out_ << bracket;
  }
  void write_string(std::string_view text) {
    out_ << '"';
    for (const char c : text) {
      switch (c) {
        case '"':
          out_ << "\\\"";
          break;
        case '\\':
          out_ << "\\\\";
          break;
        case '\b':
          out_ << "\\b";
          break;
        case '\f':
          out_ << "\\f";
          break;
        case '\n':
          out_ << "\\n";
          break;
        case '\r':
          out_ << "\\r";
          break;
        case '\t':
          out_ << "\\t";
          break;
        default:
          if (static_cast<unsigned char>(c) < 0x20) {
            char buffer[8];
            std::snprintf(buffer, sizeof buffer, "\\u%04x", static_cast<unsigned>(c));
            out_ << buffer;
          } else {
            out_ << c;  // UTF-8 passes through unchanged
          }
      }
    }
    out_ << '"';
  }

  std::ostream& out_;
  std::vector<bool> first_;  // per open container: nothing written in it yet
  bool after_key_ = false;
};

}  // namespace conicloc::tools
