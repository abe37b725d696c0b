// A JSON document model and parser (RFC 8259). Numbers are doubles; object members keep
// their order. Errors throw JsonError with the byte offset, line and column.
#pragma once

#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace handlab::util {

class JsonError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class JsonValue {
 public:
  using Array = std::vector<JsonValue>;
  using Object = std::vector<std::pair<std::string, JsonValue>>;

  JsonValue() = default;  // null
  explicit JsonValue(bool b) : v_(b) {}
  explicit JsonValue(double d) : v_(d) {}
  explicit JsonValue(std::string s) : v_(std::move(s)) {}
  explicit JsonValue(Array a) : v_(std::move(a)) {}
  explicit JsonValue(Object o) : v_(std::move(o)) {}

  static JsonValue parse(std::string_view text);

  bool is_null() const { return std::holds_alternative<std::monostate>(v_); }
  bool is_bool() const { return std::holds_alternative<bool>(v_); }
  bool is_number() const { return std::holds_alternative<double>(v_); }
  bool is_string() const { return std::holds_alternative<std::string>(v_); }
  bool is_array() const { return std::holds_alternative<Array>(v_); }
  bool is_object() const { return std::holds_alternative<Object>(v_); }

  // Typed access; throws JsonError when the value has another type.
  bool as_bool() const;
  double as_number() const;
  const std::string& as_string() const;
  const Array& as_array() const;
  const Object& as_object() const;

  // Object member, or nullptr when absent (or when this is not an object).
  const JsonValue* find(std::string_view key) const;
  // Object member; throws JsonError naming the key when absent.
  const JsonValue& operator[](std::string_view key) const;
  const JsonValue& operator[](std::size_t index) const { return as_array().at(index); }
  std::size_t size() const;
  // Compact JSON text of this value (numbers in shortest round-trip form).
  std::string dump() const;

 private:
  std::variant<std::monostate, bool, double, std::string, Array, Object> v_;
};

}  // namespace handlab::util
