#include "app/gui/headset_panel.h"

#include <algorithm>

#include <QFont>
#include <QImage>
#include <QPainter>
#include <QPixmap>
#include <QWidget>

namespace handlab::gui {
namespace {

std::shared_ptr<const render::Image> image_of(const QImage& picture) {
  const QImage rgba = picture.convertToFormat(QImage::Format_RGBA8888);
  auto image = std::make_shared<render::Image>();
  image->width = rgba.width();
  image->height = rgba.height();
  image->rgba.resize(std::size_t(image->width) * std::size_t(image->height) * 4);
  const std::size_t row = std::size_t(image->width) * 4;
  for (int y = 0; y < image->height; ++y)
    std::copy_n(rgba.constScanLine(y), row, image->rgba.data() + std::size_t(y) * row);
  return image;
}

}  // namespace

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
  return image_of(picture);
}

std::shared_ptr<const render::Image> widget_panel(QWidget& widget) {
  return image_of(widget.grab().toImage());
}

}  // namespace handlab::gui
