#include "studies/session/trial_display.h"

#include "core/hand/simulated_hand.h"

namespace handlab::studies {
namespace {

SeenHandGeometry seen_geometry(const hand::Skeleton& simulated) {
  SeenHandGeometry g;
  for (const hand::Bone& b : simulated.bones) {
    g.bone_length.push_back(b.length);
    g.bone_radius.push_back(b.radius);
  }
  g.thumb_distal = simulated.bone_index("thumb3");
  g.index_distal = simulated.bone_index("index3");
  return g;
}

}  // namespace

Observation display_observation(const task::HandCubeWorld& world, const task::SceneLayout& layout,
                                double time) {
  Observation o;
  o.time = time;
  o.bones = world.bones();
  o.thumb_touching = world.thumb_contact();
  o.index_touching = world.index_contact();
  o.cube_position = world.cube().position;
  o.cube_orientation = world.cube().orientation;
  o.cube_size = layout.cube_size;
  o.zone_a = layout.zone_a;
  o.zone_b = layout.zone_b;
  o.zone_size = layout.zone_size;
  return o;
}

SeenTrial seen_trial_of(const TrialSetup& setup, double rate_hz) {
  SeenTrial seen;
  seen.position = setup.planned.position;
  seen.rate_hz = rate_hz;
  seen.hand = seen_geometry(hand::build_simulated_hand(setup.condition.simulated_hand));
  return seen;
}

}  // namespace handlab::studies
