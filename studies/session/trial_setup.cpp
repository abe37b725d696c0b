#include "studies/session/trial_setup.h"

namespace handlab::studies {

task::SceneLayout trial_layout(const TrialSetup& setup) {
  task::SceneLayout layout = setup.protocol->scene;
  layout.cube_size = setup.condition.cube_size;
  return layout;
}

}  // namespace handlab::studies
