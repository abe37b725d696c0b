// Reads a protocol's JSON values with errors that name the file and the offending key
// ("study.json: factors[0].levels[1].method: ..."); every refusal is a ProtocolError.
#pragma once

#include <initializer_list>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/util/json_value.h"

namespace handlab::studies {

class ProtocolError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ProtocolReader {
 public:
  // `stored`: the text of a study database (the protocol.h ProtocolSource it came from).
  explicit ProtocolReader(std::string source, bool stored = false)
      : source_(std::move(source)), stored_(stored) {}
  bool stored() const { return stored_; }

  [[noreturn]] void fail(const std::string& where, const std::string& what) const;

  // Every key of `object` must be one of `known`: a misspelt key is an error, not ignored.
  void check_keys(const util::JsonValue& object, const std::string& where,
                  std::initializer_list<const char*> known) const;

  // The value of `key` in [lo, hi]; `fallback` when absent, else an error.
  double number(const util::JsonValue& object, const char* key, const std::string& where, double lo,
                double hi, std::optional<double> fallback = std::nullopt) const;
  // A length in metres in [lo, hi]: a value out of range is refused in metres and millimetres
  // as given, with a hint when it reads as millimetres written where metres are asked.
  double length(const util::JsonValue& object, const char* key, const std::string& where, double lo,
                double hi, std::optional<double> fallback = std::nullopt) const;
  int integer(const util::JsonValue& object, const char* key, const std::string& where, int lo,
              int hi, std::optional<int> fallback = std::nullopt) const;
  std::string text(const util::JsonValue& object, const char* key, const std::string& where,
                   std::optional<std::string> fallback = std::nullopt) const;
  // A factor's "levels", within or between participants: an array of two or more, each read
  // by `read(value, where)` into a level with a `name`, no label twice.
  template <typename Read>
  auto levels(const util::JsonValue& factor, const std::string& where, const std::string& name,
              Read read) const {
    const util::JsonValue* list = factor.find("levels");
    if (!list || !list->is_array()) fail(where, "\"levels\" must be an array");
    if (list->size() < 2)
      fail(where + ".levels", "a factor needs at least two levels, \"" + name + "\" has " +
                                  std::to_string(list->size()));
    std::vector<decltype(read((*list)[0], where))> out;
    std::set<std::string> labels;
    for (std::size_t k = 0; k < list->size(); ++k) {
      const std::string at = where + ".levels[" + std::to_string(k) + "]";
      out.push_back(read((*list)[k], at));
      if (!labels.insert(out.back().name).second)
        fail(at + ".name",
             "the label \"" + out.back().name + "\" is another level's of \"" + name + "\"");
    }
    return out;
  }

  // A text that becomes a column of the exports: letters, digits and '_' only.
  std::string column_name(const util::JsonValue& object, const char* key,
                          const std::string& where) const;
  // [x, y, z] in metres within 2 m of the origin.
  Eigen::Vector3d point(const util::JsonValue& object, const char* key, const std::string& where,
                        const Eigen::Vector3d& fallback) const;

 private:
  std::string source_;
  bool stored_ = false;
};

}  // namespace handlab::studies
