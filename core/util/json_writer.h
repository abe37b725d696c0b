// A streaming JSON writer: objects, arrays, strings, numbers (shortest round-trip form;
// NaN and infinities, which JSON lacks, become null), booleans and null.
#pragma once

#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace handlab::util {

class JsonWriter {
 public:
  explicit JsonWriter(std::ostream& out, int indent = 2) : out_(out), indent_(indent) {}

  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  JsonWriter& key(std::string_view name);

  JsonWriter& value(double number);
  JsonWriter& value(int number) { return value(static_cast<long long>(number)); }
  JsonWriter& value(long long number);
  // Every digit of a count or a 64-bit seed (JSON's integers have no limit; a reader that
  // keeps them as doubles rounds those past 2^53).
  JsonWriter& value(unsigned long long number);
  JsonWriter& value(std::size_t number) { return value(static_cast<unsigned long long>(number)); }
  JsonWriter& value(bool flag);
  JsonWriter& value(std::string_view text);
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  JsonWriter& null();

  template <typename T>
  JsonWriter& field(std::string_view name, const T& v) {
    key(name);
    return value(v);
  }
  JsonWriter& string_array(const std::vector<std::string>& items);

 private:
  void before_value();
  void newline();

  struct Level {
    bool is_object;
    int count;
  };
  std::ostream& out_;
  int indent_;
  std::vector<Level> stack_;
  bool after_key_ = false;
};

std::string json_escape(std::string_view text);

}  // namespace handlab::util
