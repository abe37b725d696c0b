#include "analysis/data/long_table.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>
#include <unordered_map>

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
  std::vector<std::unordered_map<std::string, int>> interned;
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
        table.columns_data_.resize(record.size());
        interned.resize(record.size());
      } else {
        if (record.size() != table.columns_.size())
          throw DataError(source_name + " line " + std::to_string(record_line) + ": " +
                          std::to_string(record.size()) + " fields, the header has " +
                          std::to_string(table.columns_.size()));
        for (std::size_t c = 0; c < record.size(); ++c) {
          Column& column = table.columns_data_[c];
          const auto [it, inserted] = interned[c].emplace(record[c], int(column.values.size()));
          if (inserted) column.values.push_back(record[c]);
          column.ids.push_back(it->second);
        }
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
  if (table.lines_.empty()) throw DataError(source_name + ": no data rows after the header");
  return table;
}

std::size_t LongTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < columns_.size(); ++i)
    if (columns_[i] == name) return i;
  std::string known;
  for (const auto& c : columns_) known += (known.empty() ? "" : ", ") + c;
  throw DataError(source_ + ": no column '" + name + "' (columns: " + known + ")");
}

LongTable::Codes LongTable::factor_codes(const std::string& name) const {
  const Column& column = columns_data_[this->column(name)];
  for (std::size_t v = 0; v < column.values.size(); ++v) {
    if (!column.values[v].empty() && column.values[v] != "NA") continue;
    const std::size_t r =
        std::size_t(std::find(column.ids.begin(), column.ids.end(), int(v)) - column.ids.begin());
    throw DataError(source_ + " line " + std::to_string(lines_[r]) + ", column '" + name +
                    "': missing value");
  }
  return {column.values, column.ids};
}

LongTable LongTable::without(const std::string& name,
                             const std::vector<std::string>& values) const {
  const std::size_t dropped = column(name);
  LongTable out;
  out.source_ = source_;
  out.columns_ = columns_;
  out.columns_data_.resize(columns_.size());
  for (std::size_t r = 0; r < rows(); ++r) {
    if (std::find(values.begin(), values.end(), cell(r, dropped)) != values.end()) continue;
    for (std::size_t k = 0; k < columns_.size(); ++k)
      out.columns_data_[k].ids.push_back(columns_data_[k].ids[r]);
    out.lines_.push_back(lines_[r]);
  }
  // Keep the values some row still has, in their order.
  for (std::size_t k = 0; k < columns_.size(); ++k) {
    const Column& from = columns_data_[k];
    Column& to = out.columns_data_[k];
    std::vector<int> renumbered(from.values.size(), -1);
    for (int id : to.ids) renumbered[std::size_t(id)] = 0;
    for (std::size_t v = 0; v < from.values.size(); ++v) {
      if (renumbered[v] < 0) continue;
      renumbered[v] = int(to.values.size());
      to.values.push_back(from.values[v]);
    }
    for (int& id : to.ids) id = renumbered[std::size_t(id)];
  }
  return out;
}

void LongTable::order_levels(const std::string& name, const std::vector<std::string>& order) {
  Column& c = columns_data_[column(name)];
  std::vector<std::size_t> sequence;  // old value indices in their new order
  for (const std::string& level : order) {
    const auto at = std::find(c.values.begin(), c.values.end(), level);
    if (at != c.values.end()) sequence.push_back(std::size_t(at - c.values.begin()));
  }
  for (std::size_t v = 0; v < c.values.size(); ++v)
    if (std::find(sequence.begin(), sequence.end(), v) == sequence.end()) sequence.push_back(v);
  std::vector<int> renumbered(c.values.size());
  std::vector<std::string> values;
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    renumbered[sequence[i]] = int(i);
    values.push_back(c.values[sequence[i]]);
  }
  c.values = std::move(values);
  for (int& id : c.ids) id = renumbered[std::size_t(id)];
}

std::vector<double> LongTable::numbers(const std::string& name) const {
  const Column& column = columns_data_[this->column(name)];
  std::vector<double> parsed(column.values.size());
  for (std::size_t v = 0; v < column.values.size(); ++v) {
    std::string_view text = column.values[v];
    while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
    while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
    if (!text.empty() && text.front() == '+') text.remove_prefix(1);
    double x = 0.0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), x);
    const bool ok = !text.empty() && error == std::errc() && end == text.data() + text.size();
    if (!ok || !std::isfinite(x)) {
      const std::size_t r =
          std::size_t(std::find(column.ids.begin(), column.ids.end(), int(v)) - column.ids.begin());
      throw DataError(source_ + " line " + std::to_string(lines_[r]) + ", column '" + name + "': " +
                      (ok ? column.values[v] + " is not a finite number"
                          : "'" + column.values[v] + "' is not a number"));
    }
    parsed[v] = x;
  }
  std::vector<double> values(rows());
  for (std::size_t r = 0; r < rows(); ++r) values[r] = parsed[std::size_t(column.ids[r])];
  return values;
}

}  // namespace handlab::analysis
