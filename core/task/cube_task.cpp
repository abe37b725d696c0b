#include "core/task/cube_task.h"

#include <cmath>
#include <stdexcept>

namespace handlab::task {

TaskObservation observe_task(const HandCubeWorld& world, double time) {
  TaskObservation o;
  o.time = time;
  o.cube_position = world.cube().position;
  o.cube_velocity = world.cube().velocity;
  o.thumb_contact = world.thumb_contact();
  o.index_contact = world.index_contact();
  return o;
}

const char* phase_name(TaskPhase phase) {
  switch (phase) {
    case TaskPhase::kReady:
      return "ready";
    case TaskPhase::kStarted:
      return "started";
    case TaskPhase::kGrasped:
      return "grasped";
    case TaskPhase::kReleased:
      return "released";
    case TaskPhase::kDone:
      return "done";
    case TaskPhase::kFailed:
      return "failed";
  }
  return "?";
}

CubeTask::CubeTask(TaskSettings settings) : settings_(std::move(settings)) {
  if (!(settings_.timeout > 0) || !(settings_.rest_time >= 0))
    throw std::invalid_argument("a task needs a positive timeout and a non-negative rest time");
}

void CubeTask::record(double time, const char* kind) {
  events_.push_back({time - start_time_, kind});
}

void CubeTask::start(double time) {
  if (phase_ != TaskPhase::kReady) throw std::logic_error("the task has already started");
  start_time_ = time;
  phase_ = TaskPhase::kStarted;
  record(time, "start");
}

bool CubeTask::in_zone_b(const Eigen::Vector3d& p) const {
  const Eigen::Vector3d& b = settings_.layout.zone_b;
  const double half = 0.5 * settings_.layout.zone_size;
  return std::abs(p.x() - b.x()) <= half && std::abs(p.z() - b.z()) <= half;
}

TaskPhase CubeTask::update(const TaskObservation& o) {
  if (phase_ == TaskPhase::kReady || finished()) return phase_;
  const double half = 0.5 * settings_.layout.cube_size;
  const bool off_floor = o.cube_position.y() - half > settings_.lift_height;
  const bool pinched = o.thumb_contact && o.index_contact;
  const bool resting = !off_floor && o.cube_velocity.norm() < settings_.rest_speed;

  switch (phase_) {
    case TaskPhase::kStarted:
      if (pinched && off_floor) {
        phase_ = TaskPhase::kGrasped;
        ++grasps_;
        record(o.time, "grasp");
      }
      break;
    case TaskPhase::kGrasped:
      if (!pinched) {
        phase_ = TaskPhase::kReleased;
        resting_since_ = -1.0;
        record(o.time, "release");
      }
      break;
    case TaskPhase::kReleased:
      if (pinched && off_floor) {  // caught again before it landed
        phase_ = TaskPhase::kGrasped;
        ++grasps_;
        record(o.time, "grasp");
      } else if (resting && !pinched) {
        // Where it stays decides, in B or out of it: a tumbling cube can pause for a step on
        // its way (below the rest speed at the top of a roll) and still end in B.
        if (resting_since_ < 0) resting_since_ = o.time;
        if (o.time - resting_since_ >= settings_.rest_time) {
          if (in_zone_b(o.cube_position)) {
            phase_ = TaskPhase::kDone;
            completion_time_ = resting_since_ - start_time_;  // when it was put down
            record(o.time, "done");
          } else {
            phase_ = TaskPhase::kStarted;
            ++drops_;
            record(resting_since_, "drop");  // when it came to rest out of B
          }
        }
      } else {
        resting_since_ = -1.0;
      }
      break;
    default:
      break;
  }
  if (!finished() && o.time - start_time_ >= settings_.timeout) {
    phase_ = TaskPhase::kFailed;
    completion_time_ = settings_.timeout;
    record(o.time, "timeout");
  }
  return phase_;
}

}  // namespace handlab::task
