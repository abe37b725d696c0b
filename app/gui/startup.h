// What the command line asks of the window once it shows: the study and screen to show, the
// participant selected, a trial played back, a session started (and its latency measured),
// the scripted pinch in the view, a screenshot taken.
#pragma once

#include <optional>

#include "app/gui/gui_options.h"

class QApplication;

namespace handlab::gui {

class MainWindow;

// Sets the shown `window` up as `options` ask; an exit status when the app must stop at once
// (the error said on stderr), nothing when it goes on. `app` quits when a screenshot or a
// latency measurement is done.
std::optional<int> start_up(MainWindow& window, const GuiOptions& options, QApplication& app);

}  // namespace handlab::gui
