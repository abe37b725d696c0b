#include "app/gui/text_table_model.h"

#include <algorithm>

namespace handlab::gui {

TextTableModel::TextTableModel(QStringList headers, QObject* parent)
    : QAbstractTableModel(parent), headers_(std::move(headers)), columns_(int(headers_.size())) {}

void TextTableModel::set_headers(QStringList headers) {
  beginResetModel();
  headers_ = std::move(headers);
  columns_ = width();
  endResetModel();
}

void TextTableModel::set_rows(std::vector<TextRow> rows) {
  beginResetModel();
  rows_ = std::move(rows);
  columns_ = width();
  endResetModel();
}

int TextTableModel::width() const {
  int columns = int(headers_.size());
  for (const TextRow& r : rows_) columns = std::max(columns, int(r.cells.size()));
  return columns;
}

QString TextTableModel::text(int row, int column) const {
  if (row < 0 || row >= int(rows_.size())) return {};
  const QStringList& cells = rows_[std::size_t(row)].cells;
  return column >= 0 && column < cells.size() ? cells[column] : QString();
}

int TextTableModel::find(int column, const QString& value) const {
  for (int r = 0; r < int(rows_.size()); ++r)
    if (text(r, column) == value) return r;
  return -1;
}

int TextTableModel::rowCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : int(rows_.size());
}

int TextTableModel::columnCount(const QModelIndex& parent) const {
  return parent.isValid() ? 0 : columns_;
}

QVariant TextTableModel::data(const QModelIndex& index, int role) const {
  if (!index.isValid()) return {};
  const TextRow& row = rows_[std::size_t(index.row())];
  switch (role) {
    case Qt::DisplayRole:
      return text(index.row(), index.column());
    case Qt::ToolTipRole:
      return index.column() == 0 && !row.tooltip.isEmpty() ? QVariant(row.tooltip) : QVariant();
    case Qt::BackgroundRole:
      return row.background.isValid() ? QVariant(row.background) : QVariant();
    default:
      return {};
  }
}

QVariant TextTableModel::headerData(int section, Qt::Orientation orientation, int role) const {
  // Rows are numbered as Qt's own models number them.
  if (orientation == Qt::Vertical)
    return QAbstractTableModel::headerData(section, orientation, role);
  if (role != Qt::DisplayRole) return {};
  return section >= 0 && section < headers_.size() ? QVariant(headers_[section]) : QVariant();
}

}  // namespace handlab::gui
