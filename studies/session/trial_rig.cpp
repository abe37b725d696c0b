#include "studies/session/trial_rig.h"

#include <algorithm>

#include "core/hand/simulated_hand.h"
#include "core/sim/hand_sim_model.h"
#include "core/task/grasp_proxy.h"

namespace handlab::studies {

struct TrialRigFactory::SoftHand {
  hand::HandShape shape;
  double cube_size = 0.0;
  hand::Skeleton skeleton;
  hand::HandFlesh flesh;
  sim::HandSimModel model;
};

TrialRigFactory::TrialRigFactory(TrackerPtr tracker, WorldKind world, double rate_hz,
                                 int sim_threads)
    : tracker_(std::move(tracker)), world_(world), rate_hz_(rate_hz), sim_threads_(sim_threads) {}

TrialRigFactory::~TrialRigFactory() = default;

// The flesh is meshed (TetGen) once per simulated hand and cube.
const TrialRigFactory::SoftHand& TrialRigFactory::soft_hand(const hand::HandShape& shape,
                                                            const hand::Skeleton& simulated,
                                                            double cube_size) {
  auto same = [&](const std::unique_ptr<SoftHand>& h) {
    return h->shape.length == shape.length && h->shape.hand_breadth() == shape.hand_breadth() &&
           h->shape.left == shape.left && h->cube_size == cube_size;
  };
  const auto found = std::find_if(soft_hands_.begin(), soft_hands_.end(), same);
  if (found != soft_hands_.end()) return **found;
  auto h = std::make_unique<SoftHand>();
  h->shape = shape;
  h->cube_size = cube_size;
  h->skeleton = simulated;
  h->flesh = hand::build_flesh(simulated, shape);
  sim::SimParameters parameters;
  parameters.cube_size = cube_size;
  h->model = sim::make_hand_sim_model(simulated, h->flesh, parameters);
  soft_hands_.push_back(std::move(h));
  return *soft_hands_.back();
}

TrialRig TrialRigFactory::build(const TrialSetup& setup) {
  TrialRig rig;
  rig.simulated = std::make_unique<const hand::Skeleton>(
      hand::build_simulated_hand(setup.condition.simulated_hand));
  rig.layout = trial_layout(setup);
  rig.timeout_s = setup.protocol->timeout_s;
  const StrategyMethod& strategy = setup.condition.strategy;
  std::optional<tracking::TrackedHandFitter> fitter;
  if (strategy.method == retarget::Strategy::kNaive) fitter = tracker_->fitter(setup.participant);
  rig.retargeter = std::make_unique<retarget::Retargeter>(strategy.method, *rig.simulated,
                                                          setup.calibration, fitter, strategy.ours);
  const Eigen::Vector3d cube_start = task::cube_start_pose(rig.layout).translation();
  if (world_ == WorldKind::kSoftHand) {
    const SoftHand& hand =
        soft_hand(setup.condition.simulated_hand, *rig.simulated, rig.layout.cube_size);
    sim::SimOptions options;
    options.threads = sim_threads_;
    auto world =
        std::make_unique<task::SoftHandWorld>(hand.model, hand.skeleton, cube_start, options);
    rig.soft = world.get();
    rig.flesh = &hand.flesh;
    rig.world = std::move(world);
  } else {
    task::GraspProxySettings settings;
    settings.cube_size = rig.layout.cube_size;
    rig.world = std::make_unique<task::GraspProxyWorld>(*rig.simulated, settings, cube_start);
  }
  task::TaskSettings task_settings;
  task_settings.layout = rig.layout;
  task_settings.rest_time = setup.protocol->rest_time_s;
  task_settings.timeout = setup.protocol->timeout_s;
  rig.task = std::make_unique<task::CubeTask>(task_settings);
  rig.task->start(0.0);
  rig.source = tracker_->open(setup, *rig.simulated, rate_hz_, cache_);
  return rig;
}

}  // namespace handlab::studies
