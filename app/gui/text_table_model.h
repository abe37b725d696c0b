// A read-only table of text for a QTableView, filled whole from what a page read (the
// participants, a schedule, a study's summary, a CSV file), with each row's tooltip and shading.
// Views show it; the page that reads the study replaces its rows.
#pragma once

#include <vector>

#include <QAbstractTableModel>
#include <QColor>
#include <QStringList>

namespace handlab::gui {

struct TextRow {
  QStringList cells;
  QString tooltip;    // on the first cell
  QColor background;  // invalid: none
};

class TextTableModel : public QAbstractTableModel {
  Q_OBJECT

 public:
  explicit TextTableModel(QStringList headers = {}, QObject* parent = nullptr);

  void set_headers(QStringList headers);
  void set_rows(std::vector<TextRow> rows);
  // The cell's text (empty outside the table).
  QString text(int row, int column) const;
  // The first row whose cell in `column` reads `value`; -1 when none does.
  int find(int column, const QString& value) const;

  int rowCount(const QModelIndex& parent = {}) const override;
  int columnCount(const QModelIndex& parent = {}) const override;
  QVariant data(const QModelIndex& index, int role) const override;
  QVariant headerData(int section, Qt::Orientation orientation, int role) const override;

 private:
  int width() const;  // the headers' or the widest row's

  QStringList headers_;
  std::vector<TextRow> rows_;
  int columns_ = 0;
};

}  // namespace handlab::gui
