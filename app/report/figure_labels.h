// Where a figure puts a point's label: beside the point, on the side with room, else above or
// below it, clear of what is already drawn there (other labels, the named points' markers).
#pragma once

#include <vector>

#include <QPointF>
#include <QRectF>

namespace handlab::report {

// The rectangle for a label `text_width` px wide beside the point `at` (`em` the font's size
// in px), inside `area` and clear of every rectangle in `taken` (the first such place, or
// beside the point if none is clear); the rectangle is added to `taken`.
QRectF place_label(QPointF at, double text_width, double em, const QRectF& area,
                   std::vector<QRectF>& taken);

}  // namespace handlab::report
