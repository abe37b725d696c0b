#include "studies/session/trial_loop.h"

#include <chrono>

#include "studies/session/session_control.h"
#include "studies/session/trial_display.h"

namespace handlab::studies {
namespace {

using Clock = std::chrono::steady_clock;

Clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

void fill_record(store::FrameRecord& r, double time, const tracking::TrackedFrame* frame,
                 const hand::HandPose* pose, const task::HandCubeWorld& world,
                 task::TaskPhase phase) {
  r.time = time;
  if (frame) {
    r.tracked = *frame;
  } else {
    r.tracked = tracking::TrackedFrame{};
    r.tracked.timestamp = time;
  }
  if (pose) {
    r.root_position = pose->root_position.cast<float>();
    r.root_rotation = Eigen::Quaternionf(pose->root_rotation.cast<float>());
    r.angles.resize(std::size_t(pose->angles.size()));
    for (Eigen::Index k = 0; k < pose->angles.size(); ++k)
      r.angles[std::size_t(k)] = float(pose->angles(k));
  }
  const auto& bones = world.bones();
  r.bone_positions.resize(bones.size());
  r.bone_rotations.resize(bones.size());
  for (std::size_t b = 0; b < bones.size(); ++b) {
    r.bone_positions[b] = bones[b].translation().cast<float>();
    r.bone_rotations[b] = Eigen::Quaternionf(bones[b].linear().cast<float>());
  }
  r.cube_position = world.cube().position.cast<float>();
  r.cube_rotation = world.cube().orientation.cast<float>();
  r.task_phase = std::uint8_t(phase);
  r.thumb_contact = world.thumb_contact();
  r.index_contact = world.index_contact();
}

// A front end's view of the step: on the soft hand, its flesh where it is now.
void report_step(SessionControl* control, const TrialRig& rig, const store::FrameRecord& record) {
  if (!control || !control->stepped) return;
  const sim::HandSimState* state = rig.soft ? rig.soft->state() : nullptr;
  control->stepped({record.time, rig.task->phase(), rig.task->grasps(), rig.task->drops(), &record,
                    state ? rig.flesh : nullptr, state ? &state->node_position : nullptr});
}

void finish(const TrialRig& rig, TrialRun& run) {
  if (rig.soft) run.simulator = rig.soft->totals();
  run.success = rig.task->phase() == task::TaskPhase::kDone;
  run.completion_time_s = rig.task->completion_time();
  run.grasps = rig.task->grasps();
  run.drops = rig.task->drops();
  for (const task::TaskEvent& e : rig.task->events()) run.events.emplace_back(e.time, e.kind);
  rig.source->finish(run);
}

}  // namespace

TrialRun run_trial(TrialRig& rig, const FrameSink& sink, const TrialLoopOptions& options) {
  const double dt = 1.0 / options.rate_hz;
  const bool real_time = options.real_time || rig.source->live();
  const Clock::time_point start = Clock::now();
  TrialRun run;
  store::FrameRecord record;
  std::optional<hand::HandPose> pose;
  Observation shown = display_observation(*rig.world, rig.layout, 0.0);
  for (long step = 1; !rig.task->finished(); ++step) {
    const double t = double(step) * dt;
    if (options.control && options.control->stop_requested()) {
      run.aborted = true;
      break;
    }
    if (real_time) rig.source->wait_for_step(start + seconds(t), seconds(dt));
    // A live tracker that stops (its runtime gone) ends the trial as aborted: kept, and run
    // again when the session resumes, not logged with a hand frozen where it was.
    if (rig.source->live() && rig.source->ended()) {
      run.aborted = true;
      run.abort_reason = "the tracker stopped sending frames";
      break;
    }
    const std::optional<tracking::TrackedFrame> frame = rig.source->next(shown);
    const tracking::TrackedHand* hand = frame ? frame->hand(tracking::Side::kRight) : nullptr;
    if (hand) pose = rig.retargeter->retarget(*hand).pose;
    rig.world->step(hand ? &*pose : nullptr, dt);
    task::TaskObservation o = task::observe_task(*rig.world, t);
    rig.task->update(o);
    fill_record(record, t, frame ? &*frame : nullptr, pose ? &*pose : nullptr, *rig.world,
                rig.task->phase());
    sink(record);
    report_step(options.control, rig, record);
    shown = display_observation(*rig.world, rig.layout, t);
    ++run.frames;
    // With the source ended and the cube at rest waiting for a grasp, nothing can happen any
    // more: the trial runs out its time at once, logged as one frame at its end (the same
    // scene, the phase it ended in), so that a replay ends where the trial did.
    if (rig.source->ended() && rig.task->phase() == task::TaskPhase::kStarted &&
        rig.world->cube().velocity.isZero()) {
      o.time = rig.timeout_s;
      rig.task->update(o);
      record.time = o.time;
      record.task_phase = std::uint8_t(rig.task->phase());
      sink(record);
      ++run.frames;
    }
  }
  finish(rig, run);
  return run;
}

}  // namespace handlab::studies
