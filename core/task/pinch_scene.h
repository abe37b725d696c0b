// The scripted pinch-and-lift's whole scene, built together: the study hand (skeleton and
// flesh at a mesh resolution), the simulator's model with the cube, and the script. The
// command line (sim bench, sim pinch) and the app's simulation view use the same one.
#pragma once

#include "core/hand/flesh.h"
#include "core/hand/hand_shape.h"
#include "core/hand/skeleton.h"
#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/task/pinch_script.h"

namespace handlab::sim {

struct PinchScene {
  hand::HandShape shape;
  hand::Skeleton skeleton;
  hand::HandFlesh flesh;
  HandSimModel model;
  PinchScript script;
  // A real recording's tracker jitter, for closings that lay it on (none when null).
  std::shared_ptr<const PoseJitter> jitter;

  // The hand above the cube on the floor, at rest, as the script starts.
  HandSimState start() const;
};

// `resolution`: the flesh mesh's (1 the study's, 4 and 16 finer); `squeeze`: how far inside
// the faces the pads' targets are (see make_pinch_script); `parameters`: the simulator's, but
// for the cube's size; `posture`: how the pinch is placed (pinch_posture.h).
PinchScene make_pinch_scene(double cube_size, int resolution = 1, double squeeze = 0.003,
                            double hand_length = 0.214, SimParameters parameters = {},
                            PinchPosture posture = PinchPosture::kSolved);

}  // namespace handlab::sim
