// The pick-and-place trial as a state machine: ready -> started -> grasped (cube off the
// floor, touched by thumb and index) -> released -> done once the cube has rested inside
// zone B for the rest time. A drop outside B goes back to waiting for a grasp; the timeout
// ends the trial as failed. It sees only what a simulator reports each step, so the same
// task runs on any hand-cube physics.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/task/hand_cube_world.h"
#include "core/task/scene_layout.h"

namespace handlab::task {

enum class TaskPhase { kReady, kStarted, kGrasped, kReleased, kDone, kFailed };
const char* phase_name(TaskPhase phase);

struct TaskSettings {
  SceneLayout layout;          // zones and cube size
  double rest_time = 0.5;      // s at rest after a release: in zone B a success, else a drop
  double timeout = 60.0;       // s from start
  double lift_height = 0.002;  // m: the cube is off the floor when its bottom is this high
  double rest_speed = 0.02;    // m/s: slower than this on the floor counts as resting
};

// What the simulation reports after a step.
struct TaskObservation {
  double time = 0.0;                                        // s
  Eigen::Vector3d cube_position = Eigen::Vector3d::Zero();  // centre (m), floor at y = 0
  Eigen::Vector3d cube_velocity = Eigen::Vector3d::Zero();
  bool thumb_contact = false, index_contact = false;
};

// What a world reports after a step at `time`.
TaskObservation observe_task(const HandCubeWorld& world, double time);

struct TaskEvent {
  double time;       // s since the trial started
  std::string kind;  // "start", "grasp", "release", "drop", "done", "timeout"
};

class CubeTask {
 public:
  explicit CubeTask(TaskSettings settings);

  void start(double time);
  TaskPhase update(const TaskObservation& observation);

  TaskPhase phase() const { return phase_; }
  bool finished() const { return phase_ == TaskPhase::kDone || phase_ == TaskPhase::kFailed; }
  int grasps() const { return grasps_; }
  int drops() const { return drops_; }
  // Time from start until the cube came to rest in B for good (s), or the timeout; 0 while
  // running.
  double completion_time() const { return completion_time_; }
  const std::vector<TaskEvent>& events() const { return events_; }
  const TaskSettings& settings() const { return settings_; }
  bool in_zone_b(const Eigen::Vector3d& cube_position) const;

 private:
  void record(double time, const char* kind);

  TaskSettings settings_;
  TaskPhase phase_ = TaskPhase::kReady;
  double start_time_ = 0.0;
  double resting_since_ = -1.0;  // time the released cube came to rest; < 0 when it is not
  int grasps_ = 0, drops_ = 0;
  double completion_time_ = 0.0;
  std::vector<TaskEvent> events_;
};

}  // namespace handlab::task
