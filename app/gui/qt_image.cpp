#include "app/gui/qt_image.h"

#include <algorithm>

namespace handlab::gui {

render::Image image_of(const QImage& picture) {
  const QImage rgba = picture.format() == QImage::Format_RGBA8888
                          ? picture
                          : picture.convertToFormat(QImage::Format_RGBA8888);
  render::Image image;
  image.width = rgba.width();
  image.height = rgba.height();
  image.rgba.resize(std::size_t(image.width) * std::size_t(image.height) * 4);
  const std::size_t row = std::size_t(image.width) * 4;
  for (int y = 0; y < image.height; ++y)
    std::copy_n(rgba.constScanLine(y), row, image.rgba.data() + std::size_t(y) * row);
  return image;
}

}  // namespace handlab::gui
