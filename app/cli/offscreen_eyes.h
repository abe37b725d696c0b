// The headset's eyes drawn offscreen in software (OSMesa), for the CLI's headset commands.
#pragma once

#include "core/xr/headset_view.h"

namespace handlab::cli {

// Each renderer made on the headset's thread (an OpenGL context is a thread's).
xr::HeadsetView::DrawerFactory offscreen_eyes();

}  // namespace handlab::cli
