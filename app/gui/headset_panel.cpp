#include "app/gui/headset_panel.h"

#include <QFont>
#include <QImage>
#include <QPainter>
#include <QPixmap>
#include <QWidget>

#include "app/gui/qt_image.h"

namespace handlab::gui {

std::shared_ptr<const render::Image> text_panel(const QString& text) {
  // 4:1, a 40 × 10 cm panel: letters about 2 cm high, read from 70 cm as 22 pt from 2 m.
  QImage picture(1024, 256, QImage::Format_RGBA8888);
  picture.fill(QColor(0x20, 0x23, 0x28));
  QPainter painter(&picture);
  QFont font = painter.font();
  font.setPixelSize(56);
  painter.setFont(font);
  painter.setPen(QColor(0xf0, 0xf0, 0xf0));
  painter.drawText(picture.rect().adjusted(32, 16, -32, -16), Qt::AlignCenter | Qt::TextWordWrap,
                   text);
  painter.end();
  return std::make_shared<const render::Image>(image_of(picture));
}

std::shared_ptr<const render::Image> widget_panel(QWidget& widget) {
  return std::make_shared<const render::Image>(image_of(widget.grab().toImage()));
}

}  // namespace handlab::gui
