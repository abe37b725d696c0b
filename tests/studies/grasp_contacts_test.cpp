// How a grasp met the cube, read from a frame log (studies/analysis/grasp_contacts.h): a made
// log whose distal phalanges are placed by hand, so that each part (tip, pad, base), the
// pinch's offset and each grasp's outcome are known.
#include <gtest/gtest.h>

#include "core/hand/simulated_hand.h"
#include "core/task/cube_task.h"
#include "studies/analysis/grasp_contacts.h"
#include "studies/analysis/grasp_tally.h"

namespace handlab::studies {
namespace {

using task::TaskPhase;

class GraspLog {
 public:
  GraspLog() : hand_(hand::build_simulated_hand(replay_.simulated_hand)) {
    replay_.layout.cube_size = 0.06;
  }
  // A frame at `phase`, the cube's centre at `cube`, each distal phalanx pointing up (+y) from
  // its joint at `thumb_joint` and `index_joint`.
  void add(TaskPhase phase, const Eigen::Vector3f& cube, const Eigen::Vector3f& thumb_joint,
           const Eigen::Vector3f& index_joint) {
    store::FrameRecord f;
    f.time = float(replay_.frames.size()) / 120.0f;
    f.task_phase = std::uint8_t(phase);
    f.cube_position = cube;
    f.bone_positions.assign(hand_.bones.size(), Eigen::Vector3f::Zero());
    f.bone_rotations.assign(hand_.bones.size(), Eigen::Quaternionf::Identity());
    f.bone_positions[std::size_t(hand_.bone_index("thumb3"))] = thumb_joint;
    f.bone_positions[std::size_t(hand_.bone_index("index3"))] = index_joint;
    replay_.frames.push_back(f);
  }
  float length(const char* bone) const {
    return float(hand_.bones[std::size_t(hand_.bone_index(bone))].length);
  }
  // The joint of a bone pointing up whose middle is at height `y`, at `x`, `z`.
  Eigen::Vector3f mid_at(const char* bone, float x, float y, float z) const {
    return {x, y - length(bone) / 2, z};
  }
  const TrialReplay& replay() const { return replay_; }

 private:
  TrialReplay replay_;
  hand::Skeleton hand_;
};

TEST(GraspContacts, TellsEachPhalanxPartThePinchOffsetAndWhatBecameOfEachGrasp) {
  GraspLog log;
  const Eigen::Vector3f cube(0.0f, 0.05f, 0.0f);
  const float li = log.length("index3");
  // The thumb's joint above the cube's centre (the bone points away from it: its base is
  // nearest), the index's a whole bone and more below it (its tip is nearest).
  const Eigen::Vector3f thumb_above(0.0f, 0.06f, -0.035f), index_below(0.004f, 0.04f - li, 0.035f);
  // Then both joints half a bone below the centre (the pads are nearest), 5 mm along x.
  const Eigen::Vector3f thumb_pad = log.mid_at("thumb3", 0.005f, 0.05f, -0.035f),
                        index_pad = log.mid_at("index3", 0.005f, 0.05f, 0.035f);
  log.add(TaskPhase::kStarted, cube, thumb_above, index_below);
  for (int k = 0; k < 3; ++k) log.add(TaskPhase::kGrasped, cube, thumb_above, index_below);
  log.add(TaskPhase::kReleased, cube, thumb_above, index_below);
  log.add(TaskPhase::kStarted, cube, thumb_above, index_below);  // it came to rest out of B
  log.add(TaskPhase::kGrasped, cube, thumb_pad, index_pad);
  log.add(TaskPhase::kReleased, cube, thumb_pad, index_pad);
  log.add(TaskPhase::kGrasped, cube, thumb_pad, index_pad);  // caught before it landed
  log.add(TaskPhase::kGrasped, cube, thumb_pad, index_pad);
  log.add(TaskPhase::kReleased, cube, thumb_pad, index_pad);
  log.add(TaskPhase::kDone, cube, thumb_pad, index_pad);

  const std::vector<GraspContact> grasps = grasp_contacts(log.replay());
  ASSERT_EQ(grasps.size(), 3u);
  EXPECT_EQ(grasps[0].outcome, GraspOutcome::kDropped);
  EXPECT_EQ(grasps[0].thumb, PhalanxPart::kBase);
  EXPECT_EQ(grasps[0].index, PhalanxPart::kTip);
  EXPECT_NEAR(grasps[0].time, 1.0 / 120, 1e-6);
  EXPECT_NEAR(grasps[0].held, 3.0 / 120, 1e-6);
  // The base's and the tip's points: the joint (y 0.06) and the tip (y 0.04), midway 0.05.
  EXPECT_NEAR(grasps[0].pinch_offset.x(), 0.002, 1e-6);
  EXPECT_NEAR(grasps[0].pinch_offset.y(), 0.0, 1e-6);
  EXPECT_NEAR(grasps[0].pinch_offset.z(), 0.0, 1e-6);
  EXPECT_EQ(grasps[1].outcome, GraspOutcome::kCaughtAgain);
  EXPECT_EQ(grasps[1].thumb, PhalanxPart::kPad);
  EXPECT_EQ(grasps[1].index, PhalanxPart::kPad);
  EXPECT_NEAR(grasps[1].pinch_offset.x(), 0.005, 1e-6);
  EXPECT_EQ(grasps[2].outcome, GraspOutcome::kPlaced);
  EXPECT_NEAR(grasps[2].held, 2.0 / 120, 1e-6);

  // Counted: the drop falls to the thumb's base and the index's tip, and to a pinch 2 mm from
  // the centre (under a fifth of the side); 5 mm is a twelfth.
  const std::vector<GraspTally> tally =
      tally_grasps({{"P01", "naive-gross", 0, 1, 0.06, grasps}}, GraspGrouping::kCube);
  ASSERT_EQ(tally.size(), 1u);
  EXPECT_EQ(tally[0].group, "6 cm");
  EXPECT_EQ(tally[0].grasps, 3);
  EXPECT_EQ(tally[0].dropped, 1);
  EXPECT_EQ(tally[0].placed, 1);
  EXPECT_EQ(tally[0].caught_again, 1);
  EXPECT_EQ(tally[0].by_thumb[std::size_t(PhalanxPart::kBase)].dropped, 1);
  EXPECT_EQ(tally[0].by_thumb[std::size_t(PhalanxPart::kPad)].grasps, 2);
  EXPECT_EQ(tally[0].by_index[std::size_t(PhalanxPart::kTip)].grasps, 1);
  EXPECT_EQ(tally[0].by_offset[0].grasps, 3);
  EXPECT_EQ(tally[0].by_offset[0].dropped, 1);
}

TEST(GraspContacts, AGraspHeldToTheTrialsEndIsUnfinishedAndFarPinchesCountApart) {
  GraspLog log;
  const Eigen::Vector3f cube(0.0f, 0.05f, 0.0f);
  // Pads 15 mm across the floor from the centre: a quarter of the 6 cm side.
  const Eigen::Vector3f thumb = log.mid_at("thumb3", 0.015f, 0.05f, -0.035f),
                        index = log.mid_at("index3", 0.015f, 0.05f, 0.035f);
  log.add(TaskPhase::kStarted, cube, thumb, index);
  log.add(TaskPhase::kGrasped, cube, thumb, index);
  log.add(TaskPhase::kGrasped, cube, thumb, index);
  const std::vector<GraspContact> grasps = grasp_contacts(log.replay());
  ASSERT_EQ(grasps.size(), 1u);
  EXPECT_EQ(grasps[0].outcome, GraspOutcome::kUnfinished);
  EXPECT_NEAR(grasps[0].held, 1.0 / 120, 1e-6);
  const auto tally =
      tally_grasps({{"P01", "ours-gross", 0, 1, 0.06, grasps}}, GraspGrouping::kCondition);
  ASSERT_EQ(tally.size(), 1u);
  EXPECT_EQ(tally[0].group, "ours-gross");
  EXPECT_EQ(tally[0].unfinished, 1);
  EXPECT_EQ(tally[0].by_offset[1].grasps, 1) << "between a fifth and two fifths of the side";
}

}  // namespace
}  // namespace handlab::studies
