#include "studies/session/trial_driver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"
#include "core/sim/hand_sim_model.h"
#include "core/task/cube_task.h"
#include "core/task/grasp_proxy.h"
#include "core/task/soft_hand_world.h"
#include "core/tracking/hand_fitting.h"
#include "core/tracking/recording_io.h"
#include "core/util/portable_random.h"
#include "studies/participant/own_hand.h"
#include "studies/participant/simulated_participant.h"
#include "studies/session/scripted_tracker.h"
#include "studies/session/session_control.h"

namespace handlab::studies {
namespace {

using tracking::Side;

task::SceneLayout layout_of(const TrialSetup& setup) {
  task::SceneLayout layout = setup.protocol->scene;
  layout.cube_size = setup.condition.cube_size;
  return layout;
}

double tip_radius(const hand::Skeleton& s) {
  const int tip = s.marker_index("index_tip");
  return s.bones[std::size_t(s.markers[std::size_t(tip)].bone)].radius;
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

std::string TrackerKind::name() const {
  switch (kind_) {
    case Kind::kScripted:
      return "scripted";
    case Kind::kRecording:
      return path_;
    case Kind::kSimulated:
      return "simulated (seed " + std::to_string(seed_) + ")";
    case Kind::kLive:
      return path_;
  }
  return path_;
}

SeenTrial seen_trial_of(const TrialSetup& setup, double rate_hz) {
  SeenTrial seen;
  seen.position = setup.planned.position;
  seen.rate_hz = rate_hz;
  seen.hand = seen_geometry(hand::build_simulated_hand(setup.condition.simulated_hand));
  return seen;
}

std::unique_ptr<SimulatedParticipant> PipelineTrialDriver::simulated_participant(
    const store::Participant& person, const SeenTrial& trial, const std::string& memory) {
  if (!own_hand_ || own_hand_length_ != person.hand_length) {
    own_hand_ = std::make_unique<OwnHand>(person.hand_length);
    own_hand_length_ = person.hand_length;
  }
  return std::make_unique<SimulatedParticipant>(
      simulated_person(person, tracker_.seed(), tracker_.participant_model()), *own_hand_, trial,
      memory.empty() ? ParticipantMemory{} : memory_from_json(memory));
}

struct PipelineTrialDriver::SoftHand {
  hand::HandShape shape;
  double cube_size = 0.0;
  hand::Skeleton skeleton;
  hand::HandFlesh flesh;
  sim::HandSimModel model;
};

PipelineTrialDriver::~PipelineTrialDriver() = default;

PipelineTrialDriver::PipelineTrialDriver(TrackerKind tracker, double rate_hz, WorldKind world,
                                         int sim_threads)
    : tracker_(std::move(tracker)), rate_hz_(rate_hz), world_(world), sim_threads_(sim_threads) {
  if (tracker_.is_recording()) {
    recording_ = tracking::read_recording(tracker_.path()).frames;
    const bool any = std::any_of(recording_.begin(), recording_.end(),
                                 [](const auto& f) { return f.hand(Side::kRight) != nullptr; });
    if (!any) throw std::runtime_error(tracker_.path() + " has no right hand to drive the trials");
  }
}

retarget::Calibration PipelineTrialDriver::calibrate(const Protocol& protocol,
                                                     const store::Participant& participant) {
  // The first condition's simulated hand (the runner rescales for conditions of other lengths).
  const Condition first = protocol.conditions().front();
  const hand::Skeleton sim = hand::build_simulated_hand(first.simulated_hand);
  // What a front end shows: the outcome, and the frame it came from.
  auto report_done = [&](const retarget::Calibration& c, tracking::TrackedFrame frame) {
    if (!control_ || !control_->calibration) return;
    CalibrationStatus status;
    status.state = CalibrationStatus::State::kDone;
    status.result = c;
    status.frame = std::move(frame);
    control_->calibration(status);
  };
  if (tracker_.is_live()) {
    // A person: the open palm held still, frame by frame, as long as it takes.
    OpenPalmCalibration step(protocol.scene, sim, participant.hand_length);
    const std::unique_ptr<tracking::LiveFrameSource> source = tracker_.open_live();
    while (!step.done()) {
      if (control_ && control_->stop_requested()) throw SessionStopped();
      // Each frame as it comes; a stop is seen within a tenth of a second without frames.
      source->wait_for_frame(std::chrono::steady_clock::now() + std::chrono::milliseconds(100));
      if (const auto frame = source->next()) {
        step.feed(*frame);
        if (control_ && control_->calibration) control_->calibration(step.status());
      }
    }
    return *step.status().result;
  }
  if (!tracker_.is_recording()) {
    // The scripted and the simulated participant hold their open palm over A for a second.
    ScriptedMotionSettings settings;
    settings.hand_length = participant.hand_length;
    settings.layout = protocol.scene;
    const std::vector<tracking::TrackedFrame> open = scripted_open_palm(settings);
    const auto calibration = retarget::calibrate_open_palm(
        open, Side::kRight, sim,
        tracking::TrackedHandFitter(participant.hand_length, Side::kRight));
    if (!calibration) throw std::runtime_error("the scripted open palm did not calibrate");
    report_done(*calibration, open.back());
    return *calibration;
  }
  // A recording: its own open-palm frames (or the length ratio without any), and the
  // recording's median palm placed 12 cm above zone A.
  retarget::Calibration c;
  auto fitter = tracking::TrackedHandFitter::for_recording(recording_, Side::kRight);
  if (auto open = retarget::calibrate_open_palm(recording_, Side::kRight, sim, *fitter))
    c = *open;
  else
    c.scale = first.simulated_hand_length /
              tracking::estimate_hand_length(recording_, Side::kRight).value();
  std::vector<double> axis[3];
  for (const auto& f : recording_)
    if (const auto* h = f.hand(Side::kRight))
      for (int i = 0; i < 3; ++i) axis[i].push_back(h->palm_position[i]);
  Eigen::Vector3d median;
  for (int i = 0; i < 3; ++i) {
    std::nth_element(axis[i].begin(), axis[i].begin() + long(axis[i].size() / 2), axis[i].end());
    median[i] = axis[i][axis[i].size() / 2];
  }
  c.tracker_to_scene =
      Eigen::Translation3d(protocol.scene.zone_a + Eigen::Vector3d(0, 0.12, 0) - median);
  report_done(c, recording_.front());
  return c;
}

std::unique_ptr<tracking::FrameSource> PipelineTrialDriver::open_tracker(
    const TrialSetup& setup, const hand::Skeleton& simulated) const {
  if (tracker_.is_scripted()) {
    ScriptedMotionSettings settings;
    settings.hand_length = setup.participant.hand_length;
    settings.scale = setup.calibration.scale;
    settings.simulated_tip_radius = tip_radius(simulated);
    settings.layout = layout_of(setup);
    settings.rate_hz = rate_hz_;
    // A person is not a metronome: each trial's tempo varies by up to 15 %, drawn from the
    // participant and the trial so that a session replays identically.
    util::PortableRandom random(
        util::fnv1a64(setup.participant.id) ^
        (0x9E3779B97F4A7C15ull * std::uint64_t(setup.planned.position + 1)));
    settings.tempo = 0.85 + 0.3 * random.uniform();
    return std::make_unique<ScriptedTracker>(settings);
  }
  tracking::ReplayOptions options;
  options.pace = tracking::ReplayPace::kResampled;
  options.rate_hz = rate_hz_;
  return std::make_unique<tracking::RecordingReplay>(recording_, options);
}

TrialRun PipelineTrialDriver::run(const TrialSetup& setup, const FrameSink& sink) {
  const Protocol& protocol = *setup.protocol;
  const hand::Skeleton sim = hand::build_simulated_hand(setup.condition.simulated_hand);
  const task::SceneLayout layout = layout_of(setup);
  const StrategyMethod& strategy = setup.condition.strategy;
  std::optional<tracking::TrackedHandFitter> fitter;
  if (strategy.method == retarget::Strategy::kNaive) {
    if (!tracker_.is_recording())
      fitter.emplace(setup.participant.hand_length, Side::kRight);
    else
      fitter = tracking::TrackedHandFitter::for_recording(recording_, Side::kRight);
  }
  retarget::Retargeter retargeter(strategy.method, sim, setup.calibration, fitter, strategy.ours);
  const Eigen::Vector3d cube_start = task::cube_start_pose(layout).translation();
  std::unique_ptr<task::HandCubeWorld> physics;
  const task::SoftHandWorld* soft = nullptr;
  const hand::HandFlesh* soft_flesh = nullptr;
  if (world_ == WorldKind::kSoftHand) {
    const hand::HandShape& shape = setup.condition.simulated_hand;
    auto same = [&](const std::unique_ptr<SoftHand>& h) {
      return h->shape.length == shape.length && h->shape.hand_breadth() == shape.hand_breadth() &&
             h->shape.left == shape.left && h->cube_size == layout.cube_size;
    };
    auto found = std::find_if(soft_hands_.begin(), soft_hands_.end(), same);
    if (found == soft_hands_.end()) {
      // The flesh is meshed (TetGen) once per simulated hand and cube.
      auto h = std::make_unique<SoftHand>();
      h->shape = shape;
      h->cube_size = layout.cube_size;
      h->skeleton = sim;
      h->flesh = hand::build_flesh(sim, shape);
      sim::SimParameters parameters;
      parameters.cube_size = layout.cube_size;
      h->model = sim::make_hand_sim_model(sim, h->flesh, parameters);
      soft_hands_.push_back(std::move(h));
      found = soft_hands_.end() - 1;
    }
    sim::SimOptions options;
    options.threads = sim_threads_;
    auto world = std::make_unique<task::SoftHandWorld>((*found)->model, (*found)->skeleton,
                                                       cube_start, options);
    soft = world.get();
    soft_flesh = &(*found)->flesh;
    physics = std::move(world);
  } else {
    task::GraspProxySettings world_settings;
    world_settings.cube_size = layout.cube_size;
    physics = std::make_unique<task::GraspProxyWorld>(sim, world_settings, cube_start);
  }
  task::HandCubeWorld& world = *physics;
  task::TaskSettings task_settings;
  task_settings.layout = layout;
  task_settings.rest_time = protocol.rest_time_s;
  task_settings.timeout = protocol.timeout_s;
  task::CubeTask task(task_settings);
  task.start(0.0);

  // A simulated participant acts on what the display showed at the last step; the other
  // trackers send their frames whatever happens.
  std::unique_ptr<tracking::FrameSource> tracker;
  tracking::LiveFrameSource* live = nullptr;  // the tracker, when live
  std::unique_ptr<SimulatedParticipant> participant;
  if (tracker_.is_simulated()) {
    participant = simulated_participant(setup.participant, seen_trial_of(setup, rate_hz_),
                                        setup.participant_memory);
  } else if (tracker_.is_live()) {
    auto source = tracker_.open_live();
    live = source.get();
    tracker = std::move(source);
  } else {
    tracker = open_tracker(setup, sim);
  }
  const double dt = 1.0 / rate_hz_;
  store::FrameRecord record;
  TrialRun run;
  bool tracker_ended = false;
  std::optional<hand::HandPose> pose;
  Observation shown = display_observation(world, layout, 0.0);
  const bool real_time = real_time_ || tracker_.is_live();
  const auto start = std::chrono::steady_clock::now();
  const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(dt));
  std::optional<tracking::TrackedFrame> held;  // a live tracker's newest frame
  for (long step = 1; !task.finished(); ++step) {
    const double t = double(step) * dt;
    if (control_ && control_->stop_requested()) {
      run.aborted = true;
      break;
    }
    if (real_time) {
      const auto due = start + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                   std::chrono::duration<double>(t));
      if (live) {
        // A frame is used as soon as it arrives, the step taken up to one step early rather
        // than the frame left waiting for its tick: the simulation keeps within a step of
        // the clock, and a frame's latency is the step's, not the step's plus the tick's.
        std::this_thread::sleep_until(due - period);
        live->wait_for_frame(due);
      } else {
        std::this_thread::sleep_until(due);
      }
    }
    std::optional<tracking::TrackedFrame> frame;
    if (participant) {
      frame = participant->act(shown);
    } else if (live) {
      if (auto fresh = live->next()) held = std::move(fresh);
      frame = held;
    } else if (!tracker_ended && !(frame = tracker->next())) {
      tracker_ended = true;
    }
    const tracking::TrackedHand* hand = frame ? frame->hand(Side::kRight) : nullptr;
    if (hand) pose = retargeter.retarget(*hand).pose;
    world.step(hand ? &*pose : nullptr, dt);
    task::TaskObservation o = task::observe_task(world, t);
    task.update(o);
    fill_record(record, t, frame ? &*frame : nullptr, pose ? &*pose : nullptr, world, task.phase());
    sink(record);
    if (control_ && control_->stepped) {
      const sim::HandSimState* state = soft ? soft->state() : nullptr;
      control_->stepped({t, task.phase(), task.grasps(), task.drops(), &record,
                         state ? soft_flesh : nullptr, state ? &state->node_position : nullptr});
    }
    if (participant) shown = display_observation(world, layout, t);
    ++run.frames;
    // With the tracker gone and the cube at rest waiting for a grasp, nothing can happen
    // any more: the trial runs out its time without further frames.
    if (tracker_ended && task.phase() == task::TaskPhase::kStarted &&
        world.cube().velocity.isZero()) {
      o.time = protocol.timeout_s;
      task.update(o);
    }
  }
  if (soft) {
    run.simulator = soft->totals();
    simulator_totals_[setup.condition.label] += run.simulator;
  }
  run.success = task.phase() == task::TaskPhase::kDone;
  run.completion_time_s = task.completion_time();
  run.grasps = task.grasps();
  run.drops = task.drops();
  for (const task::TaskEvent& e : task.events()) run.events.emplace_back(e.time, e.kind);
  if (participant) {
    run.experience = participant->experience();
    if (!run.aborted)
      participant_time_[std::round(run.experience->cube_size * 1e3) / 1e3] += run.experience->time;
    run.participant_memory = memory_to_json(participant->memory_after());
  }
  return run;
}

}  // namespace handlab::studies
