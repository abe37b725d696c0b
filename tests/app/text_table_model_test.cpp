#include "app/gui/text_table_model.h"

#include <gtest/gtest.h>

namespace handlab::gui {
namespace {

TEST(TextTableModel, ShowsItsRowsTooltipAndShadingThroughTheModelsRoles) {
  TextTableModel model({"Id", "Age"});
  EXPECT_EQ(model.rowCount(), 0);
  EXPECT_EQ(model.columnCount(), 2);
  TextRow shaded{{"P02", "41"}, {}, QColor(240, 240, 232)};
  model.set_rows({{{"P01", "24"}, "simulated participant", {}}, shaded});
  ASSERT_EQ(model.rowCount(), 2);
  EXPECT_EQ(model.data(model.index(1, 1), Qt::DisplayRole).toString(), "41");
  EXPECT_EQ(model.data(model.index(0, 0), Qt::ToolTipRole).toString(), "simulated participant");
  EXPECT_FALSE(model.data(model.index(0, 1), Qt::ToolTipRole).isValid()) << "the first cell's";
  EXPECT_FALSE(model.data(model.index(0, 0), Qt::BackgroundRole).isValid());
  EXPECT_EQ(model.data(model.index(1, 0), Qt::BackgroundRole).value<QColor>(),
            QColor(240, 240, 232));
  EXPECT_EQ(model.headerData(1, Qt::Horizontal, Qt::DisplayRole).toString(), "Age");
  EXPECT_EQ(model.headerData(1, Qt::Vertical, Qt::DisplayRole).toInt(), 2) << "rows numbered";
  EXPECT_EQ(model.find(0, "P02"), 1);
  EXPECT_EQ(model.find(0, "P09"), -1);
  EXPECT_EQ(model.text(5, 0), "") << "outside the table";
  EXPECT_EQ(model.text(0, 7), "");
}

TEST(TextTableModel, AWiderRowWidensTheTableAndAResetTellsTheViews) {
  TextTableModel model({"a"});
  int resets = 0;
  QObject::connect(&model, &QAbstractItemModel::modelReset, [&] { ++resets; });
  model.set_rows({{{"1", "2", "3"}, {}, {}}});
  EXPECT_EQ(model.columnCount(), 3);
  EXPECT_EQ(model.data(model.index(0, 2), Qt::DisplayRole).toString(), "3");
  model.set_headers({"x", "y"});
  EXPECT_EQ(model.columnCount(), 3) << "the widest row's";
  model.set_rows({});
  EXPECT_EQ(model.rowCount(), 0);
  EXPECT_EQ(model.columnCount(), 2) << "the headers'";
  EXPECT_EQ(resets, 3);
}

}  // namespace
}  // namespace handlab::gui
