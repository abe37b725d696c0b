// Two maps side by side (core/task/grasp_comparison.h) and the part of the map within half of
// every range (grasp_closing.h): closings matched by their factors, each way of changing
// counted, the half ranges' edges where the pairs grid puts them.
#include <gtest/gtest.h>

#include "core/task/grasp_comparison.h"
#include "core/task/grasp_repeats.h"

namespace handlab::sim::grasp_comparison_test {
namespace {

GraspClosing closing(const std::string& factor, double level) {
  GraspClosing c;
  set_closing_factor(c, factor, level);
  return c;
}

MappedClosing mapped(const GraspClosing& c, bool held, const std::string& factor = "pair",
                     double level = 1) {
  return {{factor, level, c}, held, held};
}

TEST(GraspComparison, WithinHalfOfEveryRangeIsThePairsGridsSpan) {
  EXPECT_TRUE(within_half_of_ranges(GraspClosing{}));
  EXPECT_TRUE(within_half_of_ranges(closing("over_closure", 0)));
  EXPECT_TRUE(within_half_of_ranges(closing("over_closure", 15)));
  EXPECT_FALSE(within_half_of_ranges(closing("over_closure", 20)));
  EXPECT_TRUE(within_half_of_ranges(closing("tilt_pitch", -15)));
  EXPECT_FALSE(within_half_of_ranges(closing("tilt_pitch", -20)));
  EXPECT_FALSE(within_half_of_ranges(closing("tilt_yaw", 30)));
  EXPECT_TRUE(within_half_of_ranges(closing("offset_along", 0.2)));
  EXPECT_FALSE(within_half_of_ranges(closing("offset_along", -0.3)));
  EXPECT_TRUE(within_half_of_ranges(closing("lead", -100)));
  EXPECT_FALSE(within_half_of_ranges(closing("lead", 200)));
  EXPECT_TRUE(within_half_of_ranges(closing("closing_speed", 2)));
  EXPECT_TRUE(within_half_of_ranges(closing("closing_speed", 10)));
  EXPECT_FALSE(within_half_of_ranges(closing("closing_speed", 20)));
  EXPECT_TRUE(within_half_of_ranges(closing("lift_acceleration", 6)));
  EXPECT_FALSE(within_half_of_ranges(closing("lift_acceleration", 12)));
  EXPECT_TRUE(within_half_of_ranges(closing("hold", 10))) << "the hold has no half";
  EXPECT_TRUE(within_half_of_ranges(closing("jitter", 4)));
  EXPECT_FALSE(within_half_of_ranges(closing("jitter", 8)));
  GraspClosing both = closing("tilt_pitch", -15);
  set_closing_factor(both, "over_closure", 20);
  EXPECT_FALSE(within_half_of_ranges(both)) << "every factor, not one";
  for (const ClosingPoint& p : factor_pairs_grid(true))
    EXPECT_TRUE(within_half_of_ranges(p.closing)) << describe(p.closing);
}

TEST(GraspComparison, CountsTheClosingsEachMapHeldClosingByClosing) {
  const GraspClosing a = closing("tilt_pitch", -15), b = closing("over_closure", 20),
                     c = closing("lead", 100), d = closing("jitter", 4);
  const std::vector<MappedClosing> before = {mapped(a, true), mapped(b, false), mapped(c, true),
                                             mapped(GraspClosing{}, true, "draw", 3)};
  const std::vector<MappedClosing> after = {mapped(c, true), mapped(a, false), mapped(b, true),
                                            mapped(d, true),
                                            mapped(GraspClosing{}, false, "draw", 4)};
  const GraspComparison cmp = compare_maps(before, after);
  EXPECT_EQ(cmp.in_both, 3);
  EXPECT_EQ(cmp.only_after, 2) << "a closing not run before, and another draw";
  EXPECT_EQ(cmp.held_before, 2);
  EXPECT_EQ(cmp.held_after, 2);
  EXPECT_EQ(cmp.released_before, 2) << "mapped() releases what it holds";
  EXPECT_EQ(cmp.released_after, 2);
  ASSERT_EQ(cmp.held_before_lost_after.size(), 1u);
  EXPECT_EQ(describe(cmp.held_before_lost_after[0].closing), "tilt_pitch -15 deg");
  ASSERT_EQ(cmp.lost_before_held_after.size(), 1u);
  EXPECT_EQ(describe(cmp.lost_before_held_after[0].closing), "over_closure 20 mm");
}

TEST(GraspComparison, TheSameClosingAsAMapFileReadsIt) {
  GraspClosing read = closing("tilt_yaw", 10);
  read.tilt_yaw = 10.0 * (M_PI / 180) * (1 + 1e-15);  // the unit's round trip through text
  EXPECT_TRUE(same_closing({"tilt_yaw", 10, closing("tilt_yaw", 10)}, {"tilt_yaw", 10, read}));
  EXPECT_FALSE(
      same_closing({"pair", 1, closing("tilt_yaw", 10)}, {"pair", 1, closing("tilt_yaw", 11)}));
  EXPECT_TRUE(same_closing({"pair", 1, GraspClosing{}}, {"", 0, GraspClosing{}}))
      << "a grid's closing is its factors, whichever grid ran it";
  EXPECT_FALSE(same_closing({"draw", 1, GraspClosing{}}, {"draw", 2, GraspClosing{}}));
  EXPECT_FALSE(same_closing({"draw", 1, GraspClosing{}}, {"", 0, GraspClosing{}}));
  GraspClosing moved;
  moved.cube_shift_x = 5e-5;
  EXPECT_FALSE(same_closing({"", 0, GraspClosing{}, 1}, {"", 0, GraspClosing{}, 0}))
      << "another repeat";
  EXPECT_FALSE(same_closing({"", 0, moved, 1}, {"", 0, GraspClosing{}, 1}));
  EXPECT_TRUE(same_closing({"", 0, moved, 1}, {"", 0, moved, 1}));
}

// With repeats, each closing's runs in both maps counted together whatever the repeat and its
// cube's move: a closing held less often (3 of 4 before, 1 of 3 now), the same draw's runs
// counted apart from another draw's, a closing the map before never ran left out.
TEST(GraspComparison, CountsEachClosingsRepeatsInBothMaps) {
  const GraspClosing a = closing("tilt_pitch", -15), c = closing("lead", 100);
  auto run = [](const GraspClosing& g, int repeat, bool held, const std::string& factor = "pair",
                double level = 1) {
    MappedClosing m = mapped(g, held, factor, level);
    m.point.repeat = repeat;
    m.point.closing.cube_shift_x = 1e-5 * repeat;
    return m;
  };
  const std::vector<MappedClosing> before = {run(a, 0, true),
                                             run(a, 1, true),
                                             run(a, 2, false),
                                             run(a, 3, true),
                                             run(GraspClosing{}, 0, true, "draw", 3),
                                             run(GraspClosing{}, 1, true, "draw", 3),
                                             run(GraspClosing{}, 0, false, "draw", 4)};
  const std::vector<MappedClosing> after = {run(GraspClosing{}, 0, false, "draw", 3),
                                            run(GraspClosing{}, 1, true, "draw", 3),
                                            run(a, 0, false),
                                            run(a, 1, true),
                                            run(a, 2, false),
                                            run(c, 0, true),
                                            run(c, 1, true)};
  const GraspComparison cmp = compare_maps(before, after);
  ASSERT_EQ(cmp.repeated.size(), 2u) << "the draw and the pitch; the lead was not run before";
  const ClosingHoldCounts& draw = cmp.repeated[0];
  EXPECT_EQ(draw.point.factor, "draw");
  EXPECT_EQ(draw.point.level, 3);
  EXPECT_EQ(draw.runs_before, 2) << "draw 4 is another closing";
  EXPECT_EQ(draw.held_before, 2);
  EXPECT_EQ(draw.runs_after, 2);
  EXPECT_EQ(draw.held_after, 1);
  const ClosingHoldCounts& pitch = cmp.repeated[1];
  EXPECT_EQ(describe(pitch.point.closing), "tilt_pitch -15 deg");
  EXPECT_EQ(pitch.point.repeat, 0);
  EXPECT_EQ(pitch.runs_before, 4);
  EXPECT_EQ(pitch.held_before, 3);
  EXPECT_EQ(pitch.runs_after, 3);
  EXPECT_EQ(pitch.held_after, 1);
  EXPECT_TRUE(compare_maps({mapped(a, true)}, {mapped(a, false)}).repeated.empty())
      << "no repeats in either map";
}

// A repeated map's closings: each with its runs, counted held every time, never or sometimes;
// within half of every range the grid's alone, not the draws.
TEST(GraspRepeats, CountsTheClosingsHeldEveryTimeNeverAndSometimes) {
  const auto run = [](const std::string& factor, const GraspClosing& c, int repeat, bool held) {
    GraspOutcome o;
    o.point = {factor, 1, c, repeat};
    o.measures.held = held;
    return o;
  };
  const GraspClosing wide = closing("over_closure", 20);
  const std::vector<GraspOutcome> outcomes = {run("", GraspClosing{}, 0, true),
                                              run("", GraspClosing{}, 1, true),
                                              run("over_closure", wide, 0, true),
                                              run("over_closure", wide, 1, false),
                                              run("draw", GraspClosing{}, 0, false),
                                              run("draw", GraspClosing{}, 1, false),
                                              run("pair", closing("lead", 100), 0, false),
                                              run("pair", closing("lead", 100), 1, true)};
  const std::vector<RepeatedClosing> closings = group_by_closing(outcomes);
  ASSERT_EQ(closings.size(), 4u);
  EXPECT_EQ(closings[1].given, &outcomes[2]);
  EXPECT_EQ(closings[1].runs, 2);
  EXPECT_EQ(closings[1].held, 1);
  const RepeatCounts all = count_repeats(closings, false);
  EXPECT_EQ(all.closings, 4);
  EXPECT_EQ(all.every, 1);
  EXPECT_EQ(all.none, 1);
  EXPECT_EQ(all.some, 2);
  const RepeatCounts half = count_repeats(closings, true);
  EXPECT_EQ(half.closings, 2) << "not 20 mm of over-closure, not a draw";
  EXPECT_EQ(half.every, 1);
  EXPECT_EQ(half.some, 1);
  EXPECT_EQ(half.none, 0);
}

}  // namespace
}  // namespace handlab::sim::grasp_comparison_test
