#include "core/task/pinch_scene.h"

#include "core/hand/simulated_hand.h"

namespace handlab::sim {

HandSimState PinchScene::start() const {
  RigidPose cube;
  cube.position = script.cube_centre;
  return initial_state(model, skeleton, script.start_root(), cube);
}

PinchScene make_pinch_scene(double cube_size, int resolution, double squeeze, double hand_length,
                            SimParameters parameters, PinchPosture posture) {
  PinchScene scene;
  scene.shape = hand::HandShape::with_length(hand_length);
  scene.skeleton = hand::build_simulated_hand(scene.shape);
  hand::FleshOptions options;
  options.resolution = resolution;
  scene.flesh = hand::build_flesh(scene.skeleton, scene.shape, options);
  parameters.cube_size = cube_size;
  scene.model = make_hand_sim_model(scene.skeleton, scene.flesh, parameters);
  scene.script = make_pinch_script(scene.skeleton, scene.model, squeeze, posture);
  return scene;
}

}  // namespace handlab::sim
