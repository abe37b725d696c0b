// A table in long format read from CSV: a header row, then one observation per row.
// Cells stay text until a caller asks for a column as numbers, so errors can name the
// column and the line.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace handlab::analysis {

class DataError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class LongTable {
 public:
  // RFC 4180 CSV: commas, double-quoted fields with "" escapes, CRLF or LF.
  static LongTable read_csv(const std::string& path);
  static LongTable parse_csv(const std::string& text, const std::string& source_name);

  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return lines_.size(); }
  // Index of a column; throws DataError naming it and the file when it is missing.
  std::size_t column(const std::string& name) const;
  const std::string& cell(std::size_t row, std::size_t column) const {
    return columns_data_[column].values[std::size_t(columns_data_[column].ids[row])];
  }
  // The file line a row came from (1-based, header is line 1).
  std::size_t line(std::size_t row) const { return lines_[row]; }
  // A column as finite numbers; throws DataError naming column and line for text, NA,
  // NaN or infinite values.
  std::vector<double> numbers(const std::string& name) const;
  // A column as a factor: each row's level index, levels in order of first appearance.
  // Empty cells and "NA" are rejected with the column and line.
  struct Codes {
    std::vector<std::string> levels;
    std::vector<int> codes;
  };
  Codes factor_codes(const std::string& name) const;
  const std::string& source() const { return source_; }
  // The table without the rows whose cell in `column` is one of `values` (levels that no
  // row keeps are gone from its factors; the others keep their order).
  LongTable without(const std::string& column, const std::vector<std::string>& values) const;
  // Puts the levels of `column` in `order` (a design's own order, which no row order may
  // change); levels it does not name follow in order of first appearance.
  void order_levels(const std::string& column, const std::vector<std::string>& order);

 private:
  // Each column's distinct values in order of first appearance and each row's index into
  // them: interned once when the file is read, so factors need no string work later.
  struct Column {
    std::vector<std::string> values;
    std::vector<int> ids;
  };
  std::string source_;
  std::vector<std::string> columns_;
  std::vector<Column> columns_data_;
  std::vector<std::size_t> lines_;
};

}  // namespace handlab::analysis
