#include "app/report/figure_labels.h"

#include <algorithm>

namespace handlab::report {

QRectF place_label(QPointF at, double text_width, double em, const QRectF& area,
                   std::vector<QRectF>& taken) {
  const double w = text_width + 0.4 * em, h = 1.4 * em;
  const bool right_first = at.x() + 0.4 * em + w <= area.right();
  std::vector<QRectF> places;
  for (double dy : {0.0, -1.3, 1.3, -2.6, 2.6, -3.9, 3.9, -5.2, 5.2})
    for (bool right : {right_first, !right_first})
      places.emplace_back(right ? at.x() + 0.4 * em : at.x() - 0.4 * em - w,
                          at.y() - 0.5 * h + dy * em, w, h);
  const auto clear = [&](const QRectF& place) {
    return area.contains(place) && std::none_of(taken.begin(), taken.end(), [&](const QRectF& t) {
             return t.intersects(place);
           });
  };
  const auto found = std::find_if(places.begin(), places.end(), clear);
  taken.push_back(found != places.end() ? *found : places.front());
  return taken.back();
}

}  // namespace handlab::report
