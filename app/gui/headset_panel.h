// The pictures on the headset's panel (render::draw_panel): the instruction as the
// participant's window words it, and the questionnaire form as it is drawn.
#pragma once

#include <memory>

#include <QString>

#include "core/render/image.h"

class QWidget;

namespace handlab::gui {

// The text in large light letters on the participant window's dark instruction bar.
std::shared_ptr<const render::Image> text_panel(const QString& text);
// The widget as it is drawn now (a questionnaire's answers as they stand).
std::shared_ptr<const render::Image> widget_panel(QWidget& widget);

}  // namespace handlab::gui
