// Reads a protocol's JSON values with errors that name the file and the offending key
// ("study.json: factors[0].levels[1].method: ..."); every refusal is a ProtocolError.
#pragma once

#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>

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
  int integer(const util::JsonValue& object, const char* key, const std::string& where, int lo,
              int hi, std::optional<int> fallback = std::nullopt) const;
  std::string text(const util::JsonValue& object, const char* key, const std::string& where,
                   std::optional<std::string> fallback = std::nullopt) const;
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
