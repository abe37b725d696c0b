#include "analysis/data/long_table.h"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace handlab::analysis {

LongTable LongTable::read_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw DataError("cannot open " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return parse_csv(text.str(), path);
}

LongTable LongTable::parse_csv(const std::string& text, const std::string& source_name) {
  LongTable table;
  table.source_ = source_name;
  std::vector<std::string> record;
  std::string field;
  std::size_t line = 1, record_line = 1;
  bool quoted = false, field_was_quoted = false;
  auto end_record = [&] {
    record.push_back(field);
    field.clear();
    const bool blank = record.size() == 1 && record[0].empty() && !field_was_quoted;
    if (!blank) {
      if (table.columns_.empty()) {
        table.columns_ = record;
      } else {
        if (record.size() != table.columns_.size())
          throw DataError(source_name + " line " + std::to_string(record_line) + ": " +
                          std::to_string(record.size()) + " fields, the header has " +
                          std::to_string(table.columns_.size()));
        table.cells_.push_back(record);
        table.lines_.push_back(record_line);
      }
    }
    record.clear();
    field_was_quoted = false;
  };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        if (c == '\n') ++line;
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
      field_was_quoted = true;
    } else if (c == ',') {
      record.push_back(field);
      field.clear();
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      end_record();
      record_line = ++line;
    } else {
      field += c;
    }
  }
  if (quoted)
    throw DataError(source_name + " line " + std::to_string(record_line) +
                    ": unterminated quoted field");
  if (!field.empty() || !record.empty()) end_record();
  if (table.columns_.empty()) throw DataError(source_name + ": the file is empty");
  for (auto& name : table.columns_) {
    if (name.size() >= 3 && name.compare(0, 3, "\xEF\xBB\xBF") == 0) name.erase(0, 3);  // BOM
  }
  if (table.cells_.empty()) throw DataError(source_name + ": no data rows after the header");
  return table;
}

std::size_t LongTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < columns_.size(); ++i)
    if (columns_[i] == name) return i;
  std::string known;
  for (const auto& c : columns_) known += (known.empty() ? "" : ", ") + c;
  throw DataError(source_ + ": no column '" + name + "' (columns: " + known + ")");
}

std::vector<double> LongTable::numbers(const std::string& name) const {
  const std::size_t col = column(name);
  std::vector<double> values(rows());
  for (std::size_t r = 0; r < rows(); ++r) {
    std::string text = cells_[r][col];
    while (!text.empty() && text.front() == ' ') text.erase(text.begin());
    while (!text.empty() && text.back() == ' ') text.pop_back();
    const char* first = text.data();
    if (!text.empty() && text[0] == '+') ++first;
    double v = 0.0;
    const auto [end, error] = std::from_chars(first, text.data() + text.size(), v);
    if (text.empty() || error != std::errc() || end != text.data() + text.size())
      throw DataError(source_ + " line " + std::to_string(lines_[r]) + ", column '" + name +
                      "': '" + cells_[r][col] + "' is not a number");
    if (!std::isfinite(v))
      throw DataError(source_ + " line " + std::to_string(lines_[r]) + ", column '" + name +
                      "': " + cells_[r][col] + " is not a finite number");
    values[r] = v;
  }
  return values;
}

}  // namespace handlab::analysis
