#include "app/report/figure_labels.h"

#include <gtest/gtest.h>

namespace handlab::report {
namespace {

// Five points bunched together (as a sensitivity figure's most influential parameters often
// are): every label lands inside the panel, clear of the others and of the points' markers.
TEST(FigureLabels, BunchedPointsGetLabelsClearOfEachOtherAndOfTheMarkers) {
  const QRectF area(0, 0, 560, 520);
  const double em = 18;
  const std::vector<QPointF> points = {{470, 250}, {400, 215}, {330, 226}, {380, 232}, {450, 229}};
  std::vector<QRectF> taken;
  for (const QPointF& at : points) taken.emplace_back(at.x() - 5, at.y() - 5, 10, 10);
  std::vector<QRectF> labels;
  for (const QPointF& at : points) labels.push_back(place_label(at, 150, em, area, taken));
  for (std::size_t i = 0; i < labels.size(); ++i) {
    EXPECT_TRUE(area.contains(labels[i])) << i;
    for (const QPointF& at : points) EXPECT_FALSE(labels[i].contains(at)) << i;
    for (std::size_t j = i + 1; j < labels.size(); ++j)
      EXPECT_FALSE(labels[i].intersects(labels[j])) << i << " and " << j;
  }
  // Beside its point, at its height, when nothing is in the way; on the left near the right edge.
  std::vector<QRectF> none;
  const QRectF free = place_label({100, 100}, 150, em, area, none);
  EXPECT_GT(free.left(), 100);
  EXPECT_NEAR(free.center().y(), 100, 1e-9);
  EXPECT_LT(place_label({540, 300}, 150, em, area, none).right(), 540);
}

}  // namespace
}  // namespace handlab::report
