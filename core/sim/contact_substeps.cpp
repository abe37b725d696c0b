#include "core/sim/contact_substeps.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/sim/contact.h"

namespace handlab::sim {
namespace {

HandSimModel substepped(HandSimModel model) {
  model.parameters.time_step /= contact_substep_count(model.parameters);
  return model;
}

}  // namespace

int contact_substep_count(const SimParameters& p) {
  return p.contact_time_step > 0 ? std::max(1, int(std::lround(p.time_step / p.contact_time_step)))
                                 : 1;
}

SubstepWindow::SubstepWindow(const SimParameters& p)
    : steps_(int(std::lround(p.contact_substep_window / p.time_step))) {}

bool ContactSubsteps::enabled(const SimParameters& parameters) {
  return contact_substep_count(parameters) > 1 && !parameters.contact_substeps_cube;
}

ContactSubsteps::ContactSubsteps(const HandSimModel& model, const SimOptions& options)
    : model_(substepped(model)),
      solver_(model_, options),
      substeps_(contact_substep_count(model.parameters)),
      window_(model.parameters) {}

bool ContactSubsteps::began_contact(const HandSimState& before, const HandSimState& after) {
  for (const ContactAnchor& a : after.node_cube)
    if (!find_anchor(before.node_cube, a.point)) return true;
  for (const ContactAnchor& a : after.sample_cube)
    if (!find_anchor(before.sample_cube, a.point)) return true;
  return false;
}

SimStepReport ContactSubsteps::step(const HandSimState& start, const std::vector<RigidPose>& from,
                                    const std::vector<RigidPose>& to, HandSimState& result) {
  SimStepReport total;
  bool touched = false;
  HandSimState current = start, next;
  std::vector<RigidPose> targets(to.size());
  for (int i = 1; i <= substeps_; ++i) {
    const double t = double(i) / substeps_;
    for (std::size_t b = 0; b < to.size(); ++b) {
      targets[b].position = (1 - t) * from[b].position + t * to[b].position;
      targets[b].rotation = from[b].rotation.slerp(t, to[b].rotation);
    }
    add_work(solver_.step(current, targets, next), total);
    // A cube touched in an early substep and let go by the last was still pushed by the hand:
    // the free cube's pass must not take the step again without it.
    touched = touched || solver_.flesh_touched_cube();
    std::swap(current, next);
  }
  touched_ = touched;
  result = std::move(current);
  return total;
}

}  // namespace handlab::sim
