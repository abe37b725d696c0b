#include "studies/analysis/grasp_contacts.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "core/hand/simulated_hand.h"
#include "core/task/cube_task.h"
#include "core/task/tracker_jitter.h"

namespace handlab::studies {
namespace {

using task::TaskPhase;

TaskPhase phase_of(const store::FrameRecord& f) {
  return TaskPhase(f.task_phase);
}

struct Phalanx {
  int bone = -1;
  double length = 0.0;
};

// The point of the phalanx's axis nearest `centre`, and which part of the phalanx that is.
std::pair<Eigen::Vector3d, PhalanxPart> nearest_part(const store::FrameRecord& f, const Phalanx& p,
                                                     const Eigen::Vector3d& centre) {
  const Eigen::Vector3d origin = f.bone_positions[std::size_t(p.bone)].cast<double>();
  const Eigen::Vector3d axis =
      f.bone_rotations[std::size_t(p.bone)].cast<double>().toRotationMatrix().col(1);
  const double along = axis.dot(centre - origin);
  const PhalanxPart part = along >= p.length ? PhalanxPart::kTip
                           : along <= 0.0    ? PhalanxPart::kBase
                                             : PhalanxPart::kPad;
  return {origin + std::clamp(along, 0.0, p.length) * axis, part};
}

// The height of the cube's lowest corner over the floor.
double lowest_corner(const store::FrameRecord& f, double side) {
  const Eigen::Matrix3d axes = f.cube_rotation.cast<double>().toRotationMatrix();
  return double(f.cube_position.y()) - 0.5 * side * axes.row(1).cwiseAbs().sum();
}

// What became of the grasp whose pinch let the cube go at frame `from`: the next phase other
// than released, and whether the cube reached the floor before a new grasp (its lowest corner
// below the height at which the task counts a cube lifted).
GraspOutcome outcome_after(const std::vector<store::FrameRecord>& frames, std::size_t from,
                           double side) {
  const double on_floor = task::TaskSettings{}.lift_height;
  bool landed = false;
  for (std::size_t k = from; k < frames.size(); ++k) {
    switch (phase_of(frames[k])) {
      case TaskPhase::kDone:
        return GraspOutcome::kPlaced;
      case TaskPhase::kStarted:
        return GraspOutcome::kDropped;
      case TaskPhase::kGrasped:
        return landed ? GraspOutcome::kLanded : GraspOutcome::kCaughtAgain;
      case TaskPhase::kReleased:
        landed = landed || lowest_corner(frames[k], side) <= on_floor;
        break;
      default:  // the trial timed out
        return GraspOutcome::kUnfinished;
    }
  }
  return GraspOutcome::kUnfinished;
}

Phalanx phalanx(const hand::Skeleton& hand, const char* name) {
  const int bone = hand.bone_index(name);
  if (bone < 0) throw std::runtime_error(std::string("the simulated hand has no bone ") + name);
  return {bone, hand.bones[std::size_t(bone)].length};
}

// The jitter of the intermediate hand the trial's frames hold.
void set_jitter(const TrialReplay& replay, TrialGrasps& trial) {
  std::vector<double> times;
  std::vector<hand::HandPose> poses;
  const hand::Skeleton hand = hand::build_simulated_hand(replay.simulated_hand);
  for (const store::FrameRecord& f : replay.frames) {
    if (f.angles.size() != hand.dofs.size()) continue;  // before the tracker saw a hand
    hand::HandPose pose;
    pose.root_position = f.root_position.cast<double>();
    pose.root_rotation = f.root_rotation.cast<double>().toRotationMatrix();
    pose.angles = Eigen::Map<const Eigen::VectorXf>(f.angles.data(), Eigen::Index(f.angles.size()))
                      .cast<double>();
    times.push_back(f.time);
    poses.push_back(std::move(pose));
  }
  if (poses.size() < 2) return;
  const sim::PoseJitter jitter = sim::pose_jitter(times, poses, 0.1);
  trial.jitter_root_rms = jitter.root_rms();
  trial.jitter_angle_rms = jitter.angle_rms();
}

}  // namespace

const char* phalanx_part_name(PhalanxPart part) {
  switch (part) {
    case PhalanxPart::kBase:
      return "base";
    case PhalanxPart::kPad:
      return "pad";
    case PhalanxPart::kTip:
      return "tip";
  }
  return "?";
}

const char* grasp_outcome_name(GraspOutcome outcome) {
  switch (outcome) {
    case GraspOutcome::kPlaced:
      return "placed";
    case GraspOutcome::kDropped:
      return "dropped";
    case GraspOutcome::kLanded:
      return "landed";
    case GraspOutcome::kCaughtAgain:
      return "caught_again";
    case GraspOutcome::kUnfinished:
      return "unfinished";
  }
  return "?";
}

bool lost(GraspOutcome outcome) {
  return outcome == GraspOutcome::kDropped || outcome == GraspOutcome::kLanded;
}

std::vector<GraspContact> grasp_contacts(const TrialReplay& replay, const ClosingReader* closings) {
  const hand::Skeleton hand = hand::build_simulated_hand(replay.simulated_hand);
  const Phalanx thumb = phalanx(hand, "thumb3"), index = phalanx(hand, "index3");
  const double side = replay.layout.cube_size;
  const std::vector<store::FrameRecord>& frames = replay.frames;
  std::vector<GraspContact> grasps;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const bool starts = phase_of(frames[k]) == TaskPhase::kGrasped &&
                        (k == 0 || phase_of(frames[k - 1]) != TaskPhase::kGrasped);
    if (!starts) continue;
    const store::FrameRecord& f = frames[k];
    if (f.bone_positions.size() != hand.bones.size() ||
        f.bone_rotations.size() != hand.bones.size())
      throw std::runtime_error("the frame at " + std::to_string(f.time) + " s holds " +
                               std::to_string(f.bone_positions.size()) +
                               " bones, the condition's hand " + std::to_string(hand.bones.size()));
    const Eigen::Vector3d centre = f.cube_position.cast<double>();
    const auto [thumb_at, thumb_part] = nearest_part(f, thumb, centre);
    const auto [index_at, index_part] = nearest_part(f, index, centre);
    GraspContact g;
    g.time = f.time;
    g.cube_size = side;
    g.thumb = thumb_part;
    g.index = index_part;
    g.pinch_offset = 0.5 * (thumb_at + index_at) - centre;
    std::size_t end = k;
    while (end < frames.size() && phase_of(frames[end]) == TaskPhase::kGrasped) ++end;
    g.held = (end < frames.size() ? frames[end].time : frames.back().time) - f.time;
    g.outcome = outcome_after(frames, end, side);
    if (closings) g.closing = closings->read(frames, k, side);
    grasps.push_back(g);
  }
  return grasps;
}

std::vector<TrialGrasps> study_grasp_contacts(store::StudyStore& store,
                                              const std::string& participant) {
  std::vector<TrialGrasps> out;
  // A reader a simulated hand, its flesh built once.
  std::vector<std::pair<hand::HandShape, std::unique_ptr<ClosingReader>>> readers;
  auto reader_for = [&](const hand::HandShape& shape) -> const ClosingReader* {
    for (const auto& [known, reader] : readers)
      if (known.length == shape.length && known.breadth == shape.breadth &&
          known.palm_thickness == shape.palm_thickness && known.tissue == shape.tissue &&
          known.left == shape.left)
        return reader.get();
    readers.emplace_back(shape, std::make_unique<ClosingReader>(shape));
    return readers.back().second.get();
  };
  for (const store::Participant& p : store.participants()) {
    if (!participant.empty() && p.id != participant) continue;
    for (const store::TrialRow& row : store.trials(p.id)) {
      const bool result = row.status == store::TrialStatus::kCompleted ||
                          row.status == store::TrialStatus::kTimeout;
      if (!result || row.frames == 0) continue;
      const TrialReplay replay = load_trial_replay(store, p.id, row.position, row.attempt);
      try {
        TrialGrasps trial;
        trial.participant = p.id;
        trial.condition = replay.condition;
        trial.position = row.position;
        trial.attempt = row.attempt;
        trial.cube_size = replay.layout.cube_size;
        trial.grasps = grasp_contacts(replay, reader_for(replay.simulated_hand));
        set_jitter(replay, trial);
        out.push_back(std::move(trial));
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(p.id + "'s trial " + std::to_string(row.position + 1) +
                                 ", attempt " + std::to_string(row.attempt) + ": " + e.what());
      }
    }
  }
  return out;
}

}  // namespace handlab::studies
