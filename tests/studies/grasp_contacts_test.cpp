// How a grasp met the cube, read from a frame log (studies/analysis/grasp_contacts.h): a made
// log whose distal phalanges and cube are placed by hand, so that each part (tip, pad, base),
// the pinch's offset and each grasp's outcome are known.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "core/hand/simulated_hand.h"
#include "core/task/cube_task.h"
#include "studies/analysis/grasp_contacts.h"
#include "studies/analysis/grasp_tally.h"

namespace handlab::studies {
namespace {

using task::TaskPhase;

// A distal phalanx as a frame logs it: its joint, and its rotation (the bone along its y).
struct Bone {
  Eigen::Vector3f joint;
  Eigen::Quaternionf rotation = Eigen::Quaternionf::Identity();
};

class GraspLog {
 public:
  GraspLog() : hand_(hand::build_simulated_hand(replay_.simulated_hand)) {
    replay_.layout.cube_size = 0.06;
  }
  // A frame at `phase` with the cube at `cube` (turned by `cube_rotation`) and the thumb's and
  // index's distal phalanges as given.
  void add(TaskPhase phase, const Eigen::Vector3f& cube, const Bone& thumb, const Bone& index,
           const Eigen::Quaternionf& cube_rotation = Eigen::Quaternionf::Identity()) {
    store::FrameRecord f;
    f.time = double(replay_.frames.size()) / 120.0;
    f.task_phase = std::uint8_t(phase);
    f.cube_position = cube;
    f.cube_rotation = cube_rotation;
    f.bone_positions.assign(hand_.bones.size(), Eigen::Vector3f::Zero());
    f.bone_rotations.assign(hand_.bones.size(), Eigen::Quaternionf::Identity());
    for (auto [name, bone] : {std::pair{"thumb3", thumb}, std::pair{"index3", index}}) {
      f.bone_positions[std::size_t(hand_.bone_index(name))] = bone.joint;
      f.bone_rotations[std::size_t(hand_.bone_index(name))] = bone.rotation;
    }
    replay_.frames.push_back(f);
  }
  float length(const char* bone) const {
    return float(hand_.bones[std::size_t(hand_.bone_index(bone))].length);
  }
  // A bone pointing up whose middle is at (x, y, z).
  Bone upright_mid_at(const char* bone, float x, float y, float z) const {
    return {{x, y - length(bone) / 2, z}};
  }
  TrialReplay& replay() { return replay_; }

 private:
  TrialReplay replay_;
  hand::Skeleton hand_;
};

TEST(GraspContacts, TellsEachPhalanxPartThePinchOffsetAndWhatBecameOfEachGrasp) {
  GraspLog log;
  const Eigen::Vector3f cube(0.0f, 0.05f, 0.0f), on_floor(0.0f, 0.03f, 0.0f);
  const float li = log.length("index3");
  // The thumb's joint above the cube's centre (the bone points away from it: its base is
  // nearest), the index's a whole bone and more below it (its tip is nearest).
  const Bone thumb_above{{0.0f, 0.06f, -0.035f}}, index_below{{0.004f, 0.04f - li, 0.035f}};
  // Then both pads level with the centre, 5 mm along x.
  const Bone thumb_pad = log.upright_mid_at("thumb3", 0.005f, 0.05f, -0.035f),
             index_pad = log.upright_mid_at("index3", 0.005f, 0.05f, 0.035f);
  log.add(TaskPhase::kStarted, cube, thumb_above, index_below);
  for (int k = 0; k < 3; ++k) log.add(TaskPhase::kGrasped, cube, thumb_above, index_below);
  log.add(TaskPhase::kReleased, cube, thumb_above, index_below);
  log.add(TaskPhase::kStarted, on_floor, thumb_above, index_below);  // at rest out of B
  log.add(TaskPhase::kGrasped, cube, thumb_pad, index_pad);
  log.add(TaskPhase::kReleased, cube, thumb_pad, index_pad);
  log.add(TaskPhase::kGrasped, cube, thumb_pad, index_pad);  // caught in the air
  log.add(TaskPhase::kReleased, cube, thumb_pad, index_pad);
  log.add(TaskPhase::kReleased, on_floor, thumb_pad, index_pad);  // it lands ...
  log.add(TaskPhase::kGrasped, cube, thumb_pad, index_pad);       // ... and is picked up
  log.add(TaskPhase::kGrasped, cube, thumb_pad, index_pad);
  log.add(TaskPhase::kReleased, on_floor, thumb_pad, index_pad);
  log.add(TaskPhase::kDone, on_floor, thumb_pad, index_pad);

  const std::vector<GraspContact> grasps = grasp_contacts(log.replay());
  ASSERT_EQ(grasps.size(), 4u);
  EXPECT_EQ(grasps[0].outcome, GraspOutcome::kDropped);
  EXPECT_EQ(grasps[0].thumb, PhalanxPart::kBase);
  EXPECT_EQ(grasps[0].index, PhalanxPart::kTip);
  EXPECT_NEAR(grasps[0].time, 1.0 / 120, 1e-9);
  EXPECT_NEAR(grasps[0].held, 3.0 / 120, 1e-9);
  // The base's and the tip's points: the joint (y 0.06) and the tip (y 0.04), midway 0.05.
  EXPECT_NEAR(grasps[0].pinch_offset.x(), 0.002, 1e-6);
  EXPECT_NEAR(grasps[0].pinch_offset.y(), 0.0, 1e-6);
  EXPECT_NEAR(grasps[0].pinch_offset.z(), 0.0, 1e-6);
  EXPECT_EQ(grasps[1].outcome, GraspOutcome::kCaughtAgain);
  EXPECT_EQ(grasps[1].thumb, PhalanxPart::kPad);
  EXPECT_EQ(grasps[1].index, PhalanxPart::kPad);
  EXPECT_NEAR(grasps[1].pinch_offset.x(), 0.005, 1e-6);
  EXPECT_EQ(grasps[2].outcome, GraspOutcome::kLanded);
  EXPECT_EQ(grasps[3].outcome, GraspOutcome::kPlaced);
  EXPECT_NEAR(grasps[3].held, 2.0 / 120, 1e-9);
  EXPECT_TRUE(lost(GraspOutcome::kDropped) && lost(GraspOutcome::kLanded));
  EXPECT_FALSE(lost(GraspOutcome::kCaughtAgain) || lost(GraspOutcome::kPlaced));

  // Counted: the drop falls to the thumb's base and the index's tip; the landing to the pads.
  const std::vector<GraspTally> tally =
      tally_grasps({{"P01", "naive-gross", 0, 1, 0.06, grasps}}, GraspGrouping::kCube);
  ASSERT_EQ(tally.size(), 1u);
  EXPECT_EQ(tally[0].group, "6 cm");
  EXPECT_EQ(tally[0].grasps, 4);
  EXPECT_EQ(tally[0].dropped, 1);
  EXPECT_EQ(tally[0].landed, 1);
  EXPECT_EQ(tally[0].lost(), 2);
  EXPECT_EQ(tally[0].placed, 1);
  EXPECT_EQ(tally[0].caught_again, 1);
  EXPECT_EQ(tally[0].by_thumb[std::size_t(PhalanxPart::kBase)].lost, 1);
  EXPECT_EQ(tally[0].by_thumb[std::size_t(PhalanxPart::kPad)].grasps, 3);
  EXPECT_EQ(tally[0].by_thumb[std::size_t(PhalanxPart::kPad)].lost, 1);
  EXPECT_EQ(tally[0].by_index[std::size_t(PhalanxPart::kTip)].grasps, 1);
  EXPECT_EQ(tally[0].by_offset[0].grasps, 4);
}

TEST(GraspContacts, ReadsTurnedBonesInTheScenesAxesAndATiltedCubeByItsLowestCorner) {
  GraspLog log;
  const float lt = log.length("thumb3"), li = log.length("index3");
  // The thumb's phalanx along -x, the index's along +x, both level at 6 cm, the index 6 mm
  // further out: the pads nearest, the pinch 1 cm above the centre and 3 mm across.
  const Eigen::Quaternionf to_minus_x(Eigen::AngleAxisf(float(M_PI / 2), Eigen::Vector3f::UnitZ()));
  const Eigen::Quaternionf to_plus_x(Eigen::AngleAxisf(-float(M_PI / 2), Eigen::Vector3f::UnitZ()));
  const Bone thumb{{lt / 2, 0.06f, -0.035f}, to_minus_x},
      index{{-li / 2, 0.06f, 0.041f}, to_plus_x};
  // The cube turned 0.5 rad about the vertical and tipped 0.3 rad: its lowest corner 3 cm x
  // (cos 0.3 + sin 0.3), 3.75 cm, below its centre: at 4 cm it is off the floor, at 3.75 cm on it.
  const Eigen::Quaternionf turned(Eigen::AngleAxisf(0.5f, Eigen::Vector3f::UnitY()) *
                                  Eigen::AngleAxisf(0.3f, Eigen::Vector3f::UnitX()));
  const Eigen::Vector3f cube(0.0f, 0.05f, 0.0f), low(0.0f, 0.04f, 0.0f), lower(0.0f, 0.0375f, 0.0f);
  log.add(TaskPhase::kGrasped, cube, thumb, index, turned);  // the trial's first frame
  log.add(TaskPhase::kReleased, low, thumb, index, turned);
  log.add(TaskPhase::kGrasped, cube, thumb, index, turned);
  log.add(TaskPhase::kReleased, lower, thumb, index, turned);
  log.add(TaskPhase::kGrasped, cube, thumb, index, turned);
  log.add(TaskPhase::kReleased, cube, thumb, index, turned);
  log.add(TaskPhase::kFailed, cube, thumb, index, turned);  // the trial timed out

  const std::vector<GraspContact> grasps = grasp_contacts(log.replay());
  ASSERT_EQ(grasps.size(), 3u);
  EXPECT_EQ(grasps[0].time, 0.0);
  EXPECT_EQ(grasps[0].thumb, PhalanxPart::kPad);
  EXPECT_EQ(grasps[0].index, PhalanxPart::kPad);
  EXPECT_NEAR(grasps[0].pinch_offset.x(), 0.0, 1e-6);
  EXPECT_NEAR(grasps[0].pinch_offset.y(), 0.01, 1e-6);
  EXPECT_NEAR(grasps[0].pinch_offset.z(), 0.003, 1e-6);
  EXPECT_EQ(grasps[0].outcome, GraspOutcome::kCaughtAgain) << "its lowest corner 2.5 mm up";
  EXPECT_EQ(grasps[1].outcome, GraspOutcome::kLanded) << "its lowest corner 0.0 mm up";
  EXPECT_EQ(grasps[2].outcome, GraspOutcome::kUnfinished);
}

TEST(GraspContacts, CountsThePinchOffsetInBinsOfTheSideAlongTheFloor) {
  // 0.19, 0.2, 0.39 and 0.4 of the side from the centre along the floor; height is not counted.
  std::vector<GraspContact> grasps;
  for (double share : {0.19, 0.2, 0.39, 0.4}) {
    GraspContact g;
    g.cube_size = 0.01;
    g.pinch_offset = Eigen::Vector3d(0.6, 0.0, 0.8) * share * 0.01 + Eigen::Vector3d(0, 0.03, 0);
    g.outcome = share < 0.3 ? GraspOutcome::kLanded : GraspOutcome::kPlaced;
    grasps.push_back(g);
  }
  const auto tally =
      tally_grasps({{"P01", "ours-fine", 0, 1, 0.01, grasps}}, GraspGrouping::kCondition);
  ASSERT_EQ(tally.size(), 1u);
  EXPECT_EQ(tally[0].group, "ours-fine");
  EXPECT_EQ(tally[0].by_offset[0].grasps, 1);
  EXPECT_EQ(tally[0].by_offset[1].grasps, 2);
  EXPECT_EQ(tally[0].by_offset[1].lost, 1);
  EXPECT_EQ(tally[0].by_offset[2].grasps, 1);
  EXPECT_EQ(tally[0].by_offset[2].lost, 0);
}

TEST(GraspContacts, AGraspedFrameWithoutTheHandIsRefused) {
  GraspLog log;
  const Bone thumb = log.upright_mid_at("thumb3", 0.0f, 0.05f, -0.035f),
             index = log.upright_mid_at("index3", 0.0f, 0.05f, 0.035f);
  log.add(TaskPhase::kGrasped, {0.0f, 0.05f, 0.0f}, thumb, index);
  log.replay().frames[0].bone_positions.clear();
  EXPECT_THROW(grasp_contacts(log.replay()), std::runtime_error);
}

}  // namespace
}  // namespace handlab::studies
