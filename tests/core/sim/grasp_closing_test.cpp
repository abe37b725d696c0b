// Closings of the grasp map (core/task/grasp_closing.h): the default closing is the scripted
// pinch to the bit, and each factor changes what it says and nothing else.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/task/grasp_map.h"
#include "core/task/human_closings.h"
#include "core/task/pinch_clearance.h"
#include "core/task/pinch_scene.h"

namespace handlab::sim::grasp_closing_test {
namespace {

const PinchScene& scene() {
  static const PinchScene s = make_pinch_scene(0.01);
  return s;
}

TEST(GraspClosing, TheDefaultClosingIsTheScriptedPinchToTheBit) {
  const PinchScript pinch = make_pinch_script(scene().skeleton, scene().model, 0.003);
  const PinchScript grasp = make_grasp_script(scene().skeleton, scene().model, GraspClosing{});
  EXPECT_EQ(grasp.hold_end, pinch.hold_end);
  EXPECT_EQ(grasp.end, pinch.end);
  EXPECT_TRUE(grasp.dof_delay.empty());
  for (double t = 0.0; t < pinch.end; t += 0.05) {
    const hand::HandPose a = pinch.target(t), b = grasp.target(t);
    EXPECT_EQ(a.angles, b.angles) << t;
    EXPECT_EQ(a.root_position, b.root_position) << t;
  }
  EXPECT_EQ(describe(GraspClosing{}), "the scripted pinch");
}

TEST(GraspClosing, OneDigitFirstSpeedAndHoldMoveTheTimeline) {
  GraspClosing closing;
  set_closing_factor(closing, "lead", 100);         // ms: the thumb first
  set_closing_factor(closing, "closing_speed", 5);  // cm/s
  set_closing_factor(closing, "hold", 2);           // s
  const PinchScript s = make_grasp_script(scene().skeleton, scene().model, closing);
  const PinchScript pinch = scene().script;
  const double closing_s = (0.015 + 0.003) / 0.05;
  EXPECT_NEAR(s.close_end - s.approach_end, closing_s, 1e-12);
  EXPECT_NEAR(s.lift_start - s.close_end, 0.1 + (pinch.lift_start - pinch.close_end), 1e-12);
  EXPECT_NEAR(s.hold_end - s.lift_end, 2.0, 1e-12);
  // Half-way through the thumb's closing the index is behind it; at the closing's end plus the
  // lead both have closed.
  const hand::Skeleton& k = scene().skeleton;
  const double mid = s.approach_end + 0.5 * closing_s;
  const hand::HandPose half = s.target(mid), closed = s.target(s.close_end + 0.1);
  int index_dofs = 0;
  for (std::size_t d = 0; d < k.dofs.size(); ++d) {
    const double span = s.pinch.angles(Eigen::Index(d)) - s.open.angles(Eigen::Index(d));
    if (std::abs(span) < 1e-6) continue;
    const double done = (half.angles(Eigen::Index(d)) - s.open.angles(Eigen::Index(d))) / span;
    if (k.dofs[d].name.rfind("index", 0) == 0) {
      ++index_dofs;
      EXPECT_LT(done, 0.5) << k.dofs[d].name;
    } else if (k.dofs[d].name.rfind("thumb", 0) == 0) {
      EXPECT_NEAR(done, 0.5, 1e-9) << k.dofs[d].name;
    }
    EXPECT_NEAR(closed.angles(Eigen::Index(d)), s.pinch.angles(Eigen::Index(d)), 1e-12);
  }
  EXPECT_GT(index_dofs, 0);
  EXPECT_EQ(describe(closing), "lead 100 ms, closing_speed 5 cm/s, hold 2 s");
}

// The lift's peak acceleration sets its length (a smoothstep of height h over T peaks at
// 6 h / T^2): 6 m/s^2 lifts the 10 cm in 0.32 s; the timeline after it moves with it.
TEST(GraspClosing, TheLiftsAccelerationSetsItsLength) {
  GraspClosing brisk;
  set_closing_factor(brisk, "lift_acceleration", 6);
  const PinchScript s = make_grasp_script(scene().skeleton, scene().model, brisk);
  const PinchScript& pinch = scene().script;
  EXPECT_NEAR(s.lift_end - s.lift_start, std::sqrt(6 * 0.10 / 6.0), 1e-12);
  EXPECT_EQ(s.lift_start, pinch.lift_start);
  EXPECT_NEAR(s.hold_end - s.lift_end, pinch.hold_end - pinch.lift_end, 1e-12);
  const double dt = 1e-4;  // the lift's acceleration at its start, by finite differences
  const auto height = [&](double t) { return s.target(t).root_position.y(); };
  EXPECT_NEAR(
      (height(s.lift_start + 2 * dt) - 2 * height(s.lift_start + dt) + height(s.lift_start)) /
          (dt * dt),
      6.0, 0.05);
  EXPECT_EQ(describe(brisk), "lift_acceleration 6 m/s2");
  EXPECT_THROW(set_closing_factor(brisk, "lift_acceleration", 0), std::invalid_argument);
}

TEST(GraspClosing, TiltAndOffsetMoveThePadsTargets) {
  GraspClosing tilted;
  set_closing_factor(tilted, "tilt_yaw", 20);
  set_closing_factor(tilted, "offset_along", 0.3);
  const PinchScript s = make_grasp_script(scene().skeleton, scene().model, tilted);
  EXPECT_NE(s.pinch.angles, scene().script.pinch.angles);
  EXPECT_LT(s.pinch_error, 0.006) << "m: the tilted, offset pinch still reaches its targets";
}

// A person closing past a face they do not feel closes the fingers on; the hand stays where it
// reached to (else the 6 cm cube's fingers came down on its top at 20 mm).
TEST(GraspClosing, OverClosureMovesTheFingersNotTheWrist) {
  GraspClosing deep;
  set_closing_factor(deep, "over_closure", 20);
  const PinchScript s = make_grasp_script(scene().skeleton, scene().model, deep);
  EXPECT_EQ(s.pinch.root_position, scene().script.pinch.root_position);
  EXPECT_NE(s.pinch.angles, scene().script.pinch.angles);
  // The scripted squeeze of `sim pinch --squeeze` still places the wrist with the pads.
  EXPECT_NE(make_pinch_script(scene().skeleton, scene().model, 0.005).pinch.root_position,
            scene().script.pinch.root_position);
}

// A tilted pinch turns the hand with its axis: the wrist's rotation turns by the tilt (where
// the pinch's rule does not place the hand again: at 20 degrees it lays other skin more than 2 mm
// into the light cube, and the rule turns the hand on).
TEST(GraspClosing, TiltTurnsTheHand) {
  GraspClosing tilted;
  set_closing_factor(tilted, "tilt_pitch", -10);
  const PinchScript s = make_grasp_script(scene().skeleton, scene().model, tilted);
  EXPECT_FALSE(s.placed_by_rule);
  const Eigen::AngleAxisd turn(s.pinch.root_rotation *
                               scene().script.pinch.root_rotation.transpose());
  EXPECT_NEAR(turn.angle(), 10 * M_PI / 180, 1e-9);
  EXPECT_NEAR(std::abs(turn.axis().x()), 1.0, 1e-9);
  set_closing_factor(tilted, "tilt_pitch", -20);
  const PinchScript placed = make_grasp_script(scene().skeleton, scene().model, tilted);
  EXPECT_TRUE(placed.placed_by_rule);
  EXPECT_GE(placed.pinch_clearance, kSkinClearance);
}

// A hand the pinch's rule places comes down in an open pose clear of the cube by the flesh's
// lag (kDescentClearance), its wrist where the pinch puts it: at a pitch of -20 degrees the
// open pose as placed before laid the index's middle phalanx 2.8 mm inside the light cube, and
// the flesh, behind its targets by about 5 mm, came down on the top.
TEST(GraspClosing, AHandTheRulePlacesComesDownClearOfTheCube) {
  GraspClosing tilted;
  set_closing_factor(tilted, "tilt_pitch", -20);
  const PinchScript placed = make_grasp_script(scene().skeleton, scene().model, tilted);
  ASSERT_TRUE(placed.placed_by_rule);
  EXPECT_GE(placed.open_clearance, kDescentClearance - 1e-5);
  EXPECT_EQ(placed.open.root_position, placed.pinch.root_position);
  EXPECT_TRUE(placed.open.root_rotation == placed.pinch.root_rotation);
  // A hand the rule leaves alone keeps the script's open pose, its skin 1.5 mm inside the cube.
  EXPECT_FALSE(scene().script.placed_by_rule);
  EXPECT_LT(scene().script.open_clearance, -0.001);
}

// The light cube's closings that the pinch's rule leaves alone come down from 5 cm as before
// the rule, so that they are the same closings to the bit.
TEST(GraspClosing, ClosingsTheRuleLeavesAloneShapeAtFiveCentimetres) {
  int left_alone = 0;
  for (const ClosingPoint& p : single_factor_grid()) {
    const PinchScript s = make_grasp_script(scene().skeleton, scene().model, p.closing);
    if (s.placed_by_rule) continue;
    ++left_alone;
    EXPECT_EQ(s.approach_height, 0.05) << describe(p.closing);
  }
  EXPECT_GT(left_alone, 40);
}

TEST(GraspClosing, UnknownFactorsAndValuesOutsideTheGridAreRefused) {
  GraspClosing c;
  EXPECT_THROW(set_closing_factor(c, "squeeze", 1), std::invalid_argument);
  EXPECT_THROW(set_closing_factor(c, "over_closure", 31), std::invalid_argument);
  EXPECT_THROW(set_closing_factor(c, "closing_speed", 0), std::invalid_argument);
  try {
    set_closing_factor(c, "lift_acceleration", 0);
    ADD_FAILURE() << "a lift of 0 m/s2";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("above 0 and at most 12 m/s2 (left out: the script's)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(set_closing_factor(c, "lead", -200));
  EXPECT_DOUBLE_EQ(c.lead_s, -0.2);
}

TEST(GraspClosing, TheGridHoldsEachFactorAloneAndThePinchOnce) {
  const std::vector<ClosingPoint> all = single_factor_grid();
  std::size_t levels = 0, jitter_levels = 0;
  for (const ClosingFactor& f : closing_factors())
    (f.name == "jitter" ? jitter_levels : levels) += f.levels.size();
  EXPECT_EQ(all.size(), levels + 1) << "the jitter only with a recording's";
  EXPECT_EQ(single_factor_grid({}, true).size(), levels + jitter_levels + 1);
  EXPECT_EQ(all.front().factor, "");
  const std::vector<ClosingPoint> lead = single_factor_grid({"lead"});
  ASSERT_EQ(lead.size(), 8u);
  EXPECT_DOUBLE_EQ(lead.back().closing.lead_s, 0.2);
  EXPECT_EQ(lead.back().closing.over_closure, GraspClosing{}.over_closure);
}

// Repeats: each closing as given, then moved cubes, within a tenth of a millimetre, drawn alike
// for the same seed and apart for another.
TEST(GraspClosing, RepeatsMoveTheCubeWithinATenthOfAMillimetre) {
  const std::vector<ClosingPoint> grid = single_factor_grid({"lead"});
  const std::vector<ClosingPoint> repeated = repeated_closings(grid, 4, 7);
  ASSERT_EQ(repeated.size(), 4 * grid.size());
  double farthest = 0.0;
  for (std::size_t i = 0; i < repeated.size(); ++i) {
    const ClosingPoint& p = repeated[i];
    const ClosingPoint& given = grid[i / 4];
    EXPECT_EQ(p.repeat, int(i % 4));
    EXPECT_EQ(p.factor, given.factor);
    EXPECT_EQ(p.closing.lead_s, given.closing.lead_s);
    const double shift = std::hypot(p.closing.cube_shift_x, p.closing.cube_shift_z);
    if (p.repeat == 0) {
      EXPECT_EQ(shift, 0.0) << "the closing as given first";
    } else {
      EXPECT_GT(shift, 0.0);
    }
    EXPECT_LE(shift, kRepeatShift);
    farthest = std::max(farthest, shift);
  }
  EXPECT_GT(farthest, 0.5 * kRepeatShift);
  const std::vector<ClosingPoint> again = repeated_closings(grid, 4, 7),
                                  other = repeated_closings(grid, 4, 8);
  EXPECT_EQ(again[5].closing.cube_shift_x, repeated[5].closing.cube_shift_x);
  EXPECT_NE(other[5].closing.cube_shift_x, repeated[5].closing.cube_shift_x);
  EXPECT_NE(repeated[5].closing.cube_shift_x, repeated[6].closing.cube_shift_x);
  // A closing's repeats move its cube alike in whatever grid it is run.
  const std::vector<ClosingPoint> whole = repeated_closings(single_factor_grid(), 4, 7);
  const auto same = std::find_if(whole.begin(), whole.end(), [&](const ClosingPoint& p) {
    return p.factor == "lead" && p.level == repeated[5].level && p.repeat == repeated[5].repeat;
  });
  ASSERT_NE(same, whole.end());
  EXPECT_EQ(same->closing.cube_shift_x, repeated[5].closing.cube_shift_x);
  EXPECT_EQ(same->closing.cube_shift_z, repeated[5].closing.cube_shift_z);
}

// A repeat moves the cube where it starts; the hand aims where it would have lain.
TEST(GraspClosing, ACubeShiftMovesTheCubeNotTheHand) {
  GraspClosing moved;
  moved.cube_shift_x = 6e-5;
  moved.cube_shift_z = -3e-5;
  const PinchScript s = make_grasp_script(scene().skeleton, scene().model, moved);
  const PinchScript given = make_grasp_script(scene().skeleton, scene().model, GraspClosing{});
  EXPECT_EQ(s.cube_centre - given.cube_centre, Eigen::Vector3d(6e-5, 0, -3e-5));
  EXPECT_EQ(s.pinch.angles, given.pinch.angles);
  EXPECT_EQ(s.pinch.root_position, given.pinch.root_position);
  EXPECT_EQ(describe(moved), "the scripted pinch") << "not a factor";
}

// A map places each placement once: closings placed alike are timed from one placement to the
// bit, and the placement reads the over-closure, tilt and offset alone.
TEST(GraspClosing, ClosingsPlacedAlikeShareTheirPlacementToTheBit) {
  const GraspClosing standard;
  const PinchScript scripted = place_grasp(scene().skeleton, scene().model, standard);
  std::vector<std::string> placing;
  for (const ClosingFactor& f : closing_factors()) {
    if (f.name == "jitter") continue;  // timed alike; needs a recording's jitter
    GraspClosing closing;
    set_closing_factor(closing, f.name, f.levels.back());
    closing.cube_shift_x = 4e-5;
    const PinchScript whole = make_grasp_script(scene().skeleton, scene().model, closing);
    if (!same_placement(standard, closing)) {
      placing.push_back(f.name);
      EXPECT_TRUE(whole.pinch.angles != scripted.pinch.angles ||
                  whole.pinch.root_position != scripted.pinch.root_position)
          << f.name;
      continue;
    }
    const PinchScript timed = time_grasp(scripted, scene().skeleton, closing);
    EXPECT_EQ(timed.cube_centre, whole.cube_centre) << f.name;
    EXPECT_EQ(timed.end, whole.end) << f.name;
    EXPECT_EQ(timed.dof_delay, whole.dof_delay) << f.name;
    for (double t = 0.0; t < whole.end; t += 0.05) {
      const hand::HandPose a = timed.target(t), b = whole.target(t);
      ASSERT_EQ(a.angles, b.angles) << f.name << " at " << t;
      ASSERT_EQ(a.root_position, b.root_position) << f.name << " at " << t;
      ASSERT_EQ(a.root_rotation, b.root_rotation) << f.name << " at " << t;
    }
  }
  EXPECT_EQ(placing,
            (std::vector<std::string>{"over_closure", "tilt_yaw", "tilt_pitch", "offset_along"}));
}

// A map runs each closing from its own placement, shared or not: the tilted closing's pads
// miss their targets as its own script's do, and the closing that shares the first placement
// is timed as its own script is (the thumb first, the lift later). The two placed as the
// scripted pinch take the scene's, which is that placement to the bit.
TEST(GraspClosing, AMapRunsEachClosingFromItsOwnPlacement) {
  GraspClosing brief, thumb_first, tilted;
  for (GraspClosing* c : {&brief, &thumb_first, &tilted}) set_closing_factor(*c, "hold", 1);
  set_closing_factor(thumb_first, "lead", 100);
  set_closing_factor(tilted, "tilt_yaw", 30);
  const std::vector<ClosingPoint> points = {
      {"hold", 1, brief}, {"pair", 1, thumb_first}, {"pair", 2, tilted}};
  int to_place = -1;
  const std::vector<GraspOutcome> map =
      run_grasp_map(scene(), points, 2, {}, [&](int, int count) { to_place = count; });
  ASSERT_EQ(map.size(), 3u);
  EXPECT_TRUE(scene().script.scripted_placement);
  EXPECT_EQ(to_place, 1) << "the tilted closing's: the others take the scene's scripted pinch";
  for (std::size_t i = 0; i < 3; ++i) {
    const PinchScript s = make_grasp_script(scene().skeleton, scene().model, points[i].closing);
    EXPECT_EQ(map[i].pinch_error_mm, 1000 * s.pinch_error) << i;
    EXPECT_EQ(map[i].open_clearance_mm, 1000 * s.open_clearance) << i;
    EXPECT_EQ(map[i].measures.step_ms.size(),
              std::size_t(pinch_step_count(s.end, scene().model.parameters.time_step)))
        << i;
  }
  EXPECT_NE(map[0].pinch_error_mm, map[2].pinch_error_mm);
  EXPECT_NE(map[0].measures.step_ms.size(), map[1].measures.step_ms.size());
}

// Which pad touched the cube first and how much earlier (pinch_loss.h): on the 6 cm cube the
// closing's lead moves the index's first touch after the thumb's by about as much, either way,
// the cube not yet turned; the light cube's solved pinch holds it with the index's middle
// phalanx, its pad never touching (none).
TEST(GraspClosing, ThePadsTouchesTellWhichDigitCameFirst) {
  static const PinchScene heavy = make_pinch_scene(0.06);
  std::vector<ClosingPoint> points;
  for (const double lead : {0.0, 200.0, -200.0}) {
    GraspClosing c;
    set_closing_factor(c, "hold", 1);
    set_closing_factor(c, "lead", lead);
    points.push_back({"lead", lead, c});
  }
  const std::vector<GraspOutcome> map = run_grasp_map(heavy, points, 2);
  ASSERT_EQ(map.size(), 3u);
  for (const GraspOutcome& o : map) {
    ASSERT_TRUE(o.touch_lead_ms.has_value()) << o.point.level;
    ASSERT_TRUE(o.turn_at_touch_deg.has_value());
    EXPECT_LT(*o.turn_at_touch_deg, 5.0) << o.point.level;
  }
  EXPECT_LT(std::abs(*map[0].touch_lead_ms), 50.0) << "the scripted pads arrive together";
  EXPECT_GT(*map[1].touch_lead_ms - *map[0].touch_lead_ms, 100.0) << "the thumb first";
  EXPECT_LT(*map[2].touch_lead_ms - *map[0].touch_lead_ms, -50.0) << "the index first";
  GraspClosing brief;
  set_closing_factor(brief, "hold", 1);
  const std::vector<GraspOutcome> light = run_grasp_map(scene(), {{"hold", 1, brief}}, 1);
  EXPECT_FALSE(light[0].touch_lead_ms.has_value());
  EXPECT_FALSE(light[0].turn_at_touch_deg.has_value());
}

// Only the scripted pinch's own placement, untimed, is taken for the closings placed as it: not
// a pinch at another squeeze, a tilted one, nor one timed (its cube moved, say).
TEST(GraspClosing, TheScriptedPlacementIsToldFromOthers) {
  EXPECT_TRUE(place_grasp(scene().skeleton, scene().model, GraspClosing{}).scripted_placement);
  EXPECT_FALSE(make_pinch_script(scene().skeleton, scene().model, 0.0).scripted_placement);
  GraspClosing tilted, moved;
  set_closing_factor(tilted, "tilt_yaw", 10);
  EXPECT_FALSE(place_grasp(scene().skeleton, scene().model, tilted).scripted_placement);
  moved.cube_shift_x = 1e-4;
  EXPECT_FALSE(time_grasp(scene().script, scene().skeleton, moved).scripted_placement);
}

// Every pair of factors at each pair of their half-range levels, once.
TEST(GraspClosing, ThePairsGridCrossesEveryTwoFactors) {
  std::size_t expected = 0, with_jitter = 0;
  const std::vector<ClosingFactor>& factors = closing_factors();
  for (std::size_t a = 0; a < factors.size(); ++a)
    for (std::size_t b = a + 1; b < factors.size(); ++b) {
      const std::size_t n = factors[a].pair_levels.size() * factors[b].pair_levels.size();
      with_jitter += n;
      if (factors[a].name != "jitter" && factors[b].name != "jitter") expected += n;
    }
  const std::vector<ClosingPoint> pairs = factor_pairs_grid();
  ASSERT_EQ(pairs.size(), expected);
  EXPECT_EQ(factor_pairs_grid(true).size(), with_jitter);
  EXPECT_EQ(pairs.front().factor, "pair");
  EXPECT_EQ(describe(pairs.front().closing), "over_closure 15 mm, tilt_yaw -15 deg");
}

// Draws of the human distribution: the same seed the same closings, each within its stated
// bounds, and every factor drawn but the hold with a source or marked an assumption.
TEST(HumanClosings, DrawsAreSeededBoundedAndSourced) {
  const std::vector<ClosingPoint> a = human_closing_draws(200, 7, 0.06),
                                  b = human_closing_draws(200, 7, 0.06);
  ASSERT_EQ(a.size(), 200u);
  double over_closure_sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const GraspClosing& c = a[i].closing;
    EXPECT_EQ(describe(c), describe(b[i].closing));
    EXPECT_EQ(a[i].factor, "draw");
    EXPECT_GT(c.over_closure, 0.0);
    EXPECT_LE(c.over_closure, 0.030);
    EXPECT_LE(std::abs(c.tilt_yaw), 30 * M_PI / 180);
    EXPECT_LE(std::abs(c.tilt_pitch), 30 * M_PI / 180);
    EXPECT_GE(c.jitter_phase, 0.0);
    EXPECT_LT(c.jitter_phase, 1.0);
    EXPECT_LE(std::abs(c.offset_along), 0.4);
    EXPECT_LE(std::abs(c.lead_s), 0.080);
    EXPECT_GE(c.closing_speed, 0.02);
    EXPECT_LE(c.closing_speed, 0.30);
    over_closure_sum += std::log(c.over_closure);
  }
  // The log-normal's median, 6 mm, within sampling error of 200 draws (SD of the mean 0.05).
  EXPECT_NEAR(std::exp(over_closure_sum / 200), 0.006, 0.001);
  EXPECT_NE(describe(human_closing_draws(1, 8, 0.06)[0].closing), describe(a[0].closing));
  for (const ClosingFactor& f : closing_factors()) {
    const auto& table = human_closing_parameters();
    const auto row = std::find_if(table.begin(), table.end(),
                                  [&](const ClosingParameter& p) { return p.factor == f.name; });
    ASSERT_NE(row, table.end()) << f.name;
    EXPECT_FALSE(row->source.empty()) << f.name;
  }
}

}  // namespace
}  // namespace handlab::sim::grasp_closing_test
