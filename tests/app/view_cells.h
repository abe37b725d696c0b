// What a table view shows, read through its model as a person reads the screen.
#pragma once

#include <QAbstractItemModel>
#include <QTableView>

namespace handlab::gui::testing {

inline int view_rows(const QTableView* view) {
  return view->model()->rowCount();
}

inline QString view_cell(const QTableView* view, int row, int column) {
  return view->model()->index(row, column).data().toString();
}

}  // namespace handlab::gui::testing
