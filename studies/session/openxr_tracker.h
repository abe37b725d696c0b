// The OpenXR runtime's hands as a session's live tracker: the headset's own session's where
// the participant wears it, else a session with no graphics (XR_MND_headless, Monado's).
#pragma once

#include "studies/session/session_headset.h"
#include "studies/session/tracker.h"

namespace handlab::studies {

// One source for the whole session (a runtime's session is not made again for every trial),
// opened now so that a missing runtime is said at once: throws std::runtime_error with the
// reason. `headset` opened with hands, or null.
TrackerPtr openxr_tracker(const SessionHeadset* headset);

}  // namespace handlab::studies
