// Fonts and painting need a QGuiApplication; without a display the offscreen platform serves
// (the report and the power curve are drawn with no display).
#pragma once

namespace handlab::cli {

void ensure_gui_application();

}  // namespace handlab::cli
