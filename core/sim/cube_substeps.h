// The cube of a step in which flesh touches it, taken again alone in substeps against the
// flesh's path (SimParameters::contact_substeps_cube: contact substeps of the cube alone). A
// multirate step (Gear & Wells 1984): the half-gram cube's contacts ring far faster than the
// hand's motion, so only the cube is integrated finer. The hand's step is the model's as
// ever; the flesh points near the cube then move on straight lines from their start to their
// end positions, as kinematic nodes (the cube cannot move them), while the cube, its floor and
// the flesh's contacts with their friction anchors are stepped in contact_time_step substeps,
// each a solve of the cube's six unknowns.
#pragma once

#include <memory>
#include <vector>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/sim/sim_options.h"

namespace handlab::sim {

class CubeSubsteps {
 public:
  // On when the parameters ask for contact substeps of the cube alone.
  static bool enabled(const SimParameters& parameters);

  // `hand` must outlive this.
  explicit CubeSubsteps(const HandSimModel& hand);
  ~CubeSubsteps();
  CubeSubsteps(const CubeSubsteps&) = delete;
  CubeSubsteps& operator=(const CubeSubsteps&) = delete;

  // The flesh points whose path the cube's substeps take: within this of the cube at the
  // step's start, beyond what they and the cube move in the step (m). A new set of points
  // takes those within twice this, so that it and its solver last while the hand moves a
  // little.
  static constexpr double kReach = 0.002;

  // `result`, the hand's step from `start`, gets the cube's pose, velocity and floor and flesh
  // anchors of the substeps; its flesh and bones are left as they are. The report is the last
  // substep's (its deepest flesh point inside the cube).
  SimStepReport step(const HandSimState& start, HandSimState& result);

  // A flesh point of the hand: a surface node or a skin sample (nodes first, then samples).
  struct FleshPoint {
    bool sample = false;
    int index = 0;
    auto operator<=>(const FleshPoint&) const = default;
  };

 private:
  struct Points;
  const HandSimModel& hand_;
  int substeps_ = 1;
  std::unique_ptr<Points> points_;  // the last set, its model and solver
};

}  // namespace handlab::sim
