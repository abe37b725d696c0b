// The columns a study's export writes whatever its protocol: each file is the participant's
// columns, the between factors', the design's, the within factors', then its own. Read by the
// export (studies/export), which writes them, and by the protocol, which refuses a factor or
// an item named as one of them (it would write a second).
#pragma once

#include <string>
#include <vector>

namespace handlab::studies {

inline constexpr const char* kParticipantColumns[] = {
    "participant", "age", "sex", "handedness", "hand_length", "vr_experience"};
inline constexpr const char* kDesignColumns[] = {"block", "order"};
inline constexpr const char* kTrialColumns[] = {
    "repetition", "completion_time_s", "outcome", "grasps", "drops", "attempt"};
inline constexpr const char* kFrameColumns[] = {
    "repetition",    "attempt",         "outcome",     "t",
    "phase",         "cube_x",          "cube_y",      "cube_z",
    "thumb_contact", "index_contact",   "thumb_tip_x", "thumb_tip_y",
    "thumb_tip_z",   "index_tip_x",     "index_tip_y", "index_tip_z",
    "aperture",      "tracked_aperture"};

// Every column the three files write whatever the protocol, each once.
std::vector<std::string> fixed_export_columns();

}  // namespace handlab::studies
