// The markers the figures tell series apart by, in greyscale as in colour: circle, square,
// triangle and diamond, then again. The painter's pen and brush draw them.
#pragma once

#include <QPointF>

class QPainter;

namespace handlab::report {

// Marker `shape` (any number; four shapes in turn) centred at `at`, `radius` px.
void draw_marker(QPainter& p, int shape, QPointF at, double radius);

}  // namespace handlab::report
