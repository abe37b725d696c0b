// One trial's parts, built from its set-up by one factory: the simulated hand in its world
// (the grasp proxy or the soft hand), the retargeter, the task and the frame source. The
// factory keeps what is costly to build between trials: the soft hand's meshed flesh (once a
// hand and cube) and the tracker's TrialCache.
#pragma once

#include <memory>
#include <vector>

#include "core/hand/flesh.h"
#include "core/hand/skeleton.h"
#include "core/retarget/retargeter.h"
#include "core/task/cube_task.h"
#include "core/task/hand_cube_world.h"
#include "core/task/scene_layout.h"
#include "core/task/soft_hand_world.h"
#include "studies/session/tracker.h"
#include "studies/session/trial_frame_source.h"
#include "studies/session/trial_setup.h"

namespace handlab::studies {

// The hand-cube physics a trial runs on: the grasp proxy (the cube attaches to a pinch,
// core/task/grasp_proxy.h) or the soft-hand simulator (contact and friction only,
// core/task/soft_hand_world.h, docs/simulator.md).
enum class WorldKind { kGraspProxy, kSoftHand };

// The retargeter and the grasp proxy hold the simulated hand by reference: it lives on the
// heap, so the rig can move.
struct TrialRig {
  std::unique_ptr<const hand::Skeleton> simulated;  // the condition's hand
  task::SceneLayout layout;  // the protocol's scene with the condition's cube
  double timeout_s = 0.0;
  std::unique_ptr<task::HandCubeWorld> world;
  const task::SoftHandWorld* soft = nullptr;  // the world, when it is the soft hand
  const hand::HandFlesh* flesh = nullptr;     // and its flesh
  std::unique_ptr<retarget::Retargeter> retargeter;
  std::unique_ptr<task::CubeTask> task;  // started at 0
  std::unique_ptr<TrialFrameSource> source;
};

class TrialRigFactory {
 public:
  // `sim_threads`: the soft-hand simulator's threads (1 when sessions run side by side).
  TrialRigFactory(TrackerPtr tracker, WorldKind world, double rate_hz, int sim_threads);
  ~TrialRigFactory();
  TrialRig build(const TrialSetup& setup);

 private:
  struct SoftHand;  // a simulated hand's flesh and model for a cube
  const SoftHand& soft_hand(const hand::HandShape& shape, const hand::Skeleton& simulated,
                            double cube_size);

  TrackerPtr tracker_;
  WorldKind world_;
  double rate_hz_;
  int sim_threads_;
  std::vector<std::unique_ptr<SoftHand>> soft_hands_;
  TrialCache cache_;
};

}  // namespace handlab::studies
