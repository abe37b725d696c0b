// The headset's eyes drawn with the app's own OpenGL (a Qt context on the headset's thread,
// drawing into a framebuffer object and read back), where the CLI uses OSMesa: the app never
// links OSMesa (its gl* symbols clash with the system libGL's).
#pragma once

#include <memory>

#include "core/xr/headset_view.h"

class QOffscreenSurface;

namespace handlab::gui {

class HeadsetEyes {
 public:
  // On the GUI thread (where Qt makes surfaces): the surface the headset's thread draws on.
  // Throws std::runtime_error where the display has none to give.
  HeadsetEyes();
  ~HeadsetEyes();
  HeadsetEyes(const HeadsetEyes&) = delete;
  HeadsetEyes& operator=(const HeadsetEyes&) = delete;

  // Each eye drawer it makes owns a context of its own, made on the thread that calls it;
  // valid while this lives. Throws std::runtime_error there where OpenGL 3.3 is not to be had.
  xr::HeadsetView::DrawerFactory factory() const;

 private:
  std::unique_ptr<QOffscreenSurface> surface_;
};

}  // namespace handlab::gui
