// Qt's pictures as the renderer's images.
#pragma once

#include <QImage>

#include "core/render/image.h"

namespace handlab::gui {

// The picture's pixels as 8-bit RGBA, rows top to bottom (converted where it is another format).
render::Image image_of(const QImage& picture);

}  // namespace handlab::gui
