#include "studies/protocol/protocol_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/util/csv.h"

namespace handlab::studies {

using util::JsonValue;

void ProtocolReader::fail(const std::string& where, const std::string& what) const {
  throw ProtocolError(source_ + ": " + where + ": " + what);
}

void ProtocolReader::check_keys(const JsonValue& object, const std::string& where,
                                std::initializer_list<const char*> known) const {
  if (!object.is_object()) fail(where, "must be an object");
  for (const auto& [key, value] : object.as_object()) {
    if (std::none_of(known.begin(), known.end(), [&](const char* k) { return key == k; })) {
      std::string list;
      for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + k;
      fail(where, "unknown key \"" + key + "\" (known: " + list + ")");
    }
  }
}

double ProtocolReader::number(const JsonValue& object, const char* key, const std::string& where,
                              double lo, double hi, std::optional<double> fallback) const {
  const JsonValue* v = object.find(key);
  if (!v) {
    if (fallback) return *fallback;
    fail(where, std::string("\"") + key + "\" is required");
  }
  if (!v->is_number()) fail(where + "." + key, "must be a number");
  const double x = v->as_number();
  if (!(x >= lo && x <= hi))
    fail(where + "." + key, "must be from " + util::format_number(lo) + " to " +
                                util::format_number(hi) + ", is " + util::format_number(x));
  return x;
}

double ProtocolReader::length(const JsonValue& object, const char* key, const std::string& where,
                              double lo, double hi, std::optional<double> fallback) const {
  const double inf = std::numeric_limits<double>::infinity();
  const double x = number(object, key, where, -inf, inf, fallback);
  if (x >= lo && x <= hi) return x;
  auto mm = [](double metres) { return util::format_number(metres * 1000.0) + " mm"; };
  std::string why = "a length in metres from " + util::format_number(lo) + " to " +
                    util::format_number(hi) + " (" + mm(lo) + " to " + mm(hi) + "), is " +
                    util::format_number(x) + " m (" + mm(x) + ")";
  if (x / 1000.0 >= lo && x / 1000.0 <= hi)
    why += ": in metres, " + util::format_number(x) + " mm is " + util::format_number(x / 1000.0);
  fail(where + "." + key, why);
}

int ProtocolReader::integer(const JsonValue& object, const char* key, const std::string& where,
                            int lo, int hi, std::optional<int> fallback) const {
  const double x = number(object, key, where, lo, hi,
                          fallback ? std::optional<double>(*fallback) : std::nullopt);
  if (x != std::floor(x)) fail(where + "." + key, "must be a whole number");
  return int(x);
}

std::string ProtocolReader::text(const JsonValue& object, const char* key, const std::string& where,
                                 std::optional<std::string> fallback) const {
  const JsonValue* v = object.find(key);
  if (!v) {
    if (fallback) return *fallback;
    fail(where, std::string("\"") + key + "\" is required");
  }
  if (!v->is_string() || v->as_string().empty())
    fail(where + "." + key, "must be a non-empty string");
  return v->as_string();
}

Eigen::Vector3d ProtocolReader::point(const JsonValue& object, const char* key,
                                      const std::string& where,
                                      const Eigen::Vector3d& fallback) const {
  const JsonValue* v = object.find(key);
  if (!v) return fallback;
  if (!v->is_array() || v->size() != 3) fail(where + "." + key, "must be [x, y, z] in metres");
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) {
    if (!(*v)[std::size_t(i)].is_number()) fail(where + "." + key, "must hold numbers");
    p[i] = (*v)[std::size_t(i)].as_number();
    if (std::abs(p[i]) > 2.0) fail(where + "." + key, "is more than 2 m from the origin");
  }
  return p;
}

std::string ProtocolReader::column_name(const JsonValue& object, const char* key,
                                        const std::string& where) const {
  const std::string name = text(object, key, where);
  const bool identifier = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
  if (!identifier) fail(where + "." + key, "use letters, digits and '_' (it becomes a column)");
  return name;
}

}  // namespace handlab::studies
