// The study hand pinches each of the study's cubes between thumb and index on the scripted
// pinch-and-lift (core/task/pinch_script.h): it lifts it 10 cm and holds it 5 s without letting
// it slip or sink into the flesh, and opening the fingers lets it fall back to the floor.
#include <array>
#include <initializer_list>
#include <iostream>
#include <numeric>

#include <gtest/gtest.h>

#include "core/hand/hand_shape.h"
#include "core/sim/box_distance.h"
#include "core/sim/contact_forces.h"
#include "core/task/pinch_clearance.h"
#include "core/task/pinch_scene.h"
#include "tests/support/under_sanitizers.h"

namespace handlab::sim {
namespace {

class Pinch : public testing::TestWithParam<double> {};

TEST_P(Pinch, LiftsHoldsAndReleasesTheCube) {
  const PinchScene scene = make_pinch_scene(GetParam());
  const HandSimModel& model = scene.model;
  const hand::Skeleton& skeleton = scene.skeleton;
  const PinchScript& script = scene.script;
  ASSERT_LT(script.pinch_error, 0.005) << "m: the scripted pinch should reach the faces";
  double highest = 0.0;
  const PinchReport r = run_pinch(model, skeleton, script, {}, 0.0, [&](const HandSimState& s) {
    if (s.time <= script.hold_end) highest = std::max(highest, s.cube_pose.position.y());
  });
  std::cout << "cube " << GetParam() * 100 << " cm: lifted " << r.lift * 100 << " cm, slip "
            << r.slip_mm << " mm, penetration " << r.max_penetration_mm << " mm\n";
  EXPECT_TRUE(r.held);
  EXPECT_GT(r.lift, 0.08) << "m, of the hand's 0.10";
  EXPECT_LT(r.slip_mm, 1.0);
  // At the flesh's nodes and skin samples: the heavy cube (108 g, 200 times the light one)
  // presses further into the pads.
  EXPECT_LT(r.max_penetration_mm, GetParam() < 0.03 ? 0.5 : 1.5);
  EXPECT_TRUE(r.released) << "opening the fingers should drop it back on the floor";
  // The flesh stays sound: a few tets of the light cube's pinch, where the knuckles press its
  // top, are inside out (6), none of the heavy cube's; with the stiffening off the thumb's
  // base tangles (39 of the light cube's, their rotations flipping from step to step).
  EXPECT_LE(r.inverted_tets, 10);
  EXPECT_LT(highest - script.cube_centre.y(), script.lift_height + 0.01) << "m: flung upwards";
  // Holding still, the energy and its gradient agree: the line search takes Newton's step
  // whole (a friction spring whose normal turned with the cube once made it halve the step
  // seven times a step in the hold).
  const double h = model.parameters.time_step;
  int hold_steps = 0, halvings = 0;
  for (std::size_t i = 0; i < r.halvings.size(); ++i) {
    const double t = double(i + 1) * h;
    if (t < script.lift_end + 0.5 || t > script.hold_end) continue;
    ++hold_steps;
    halvings += r.halvings[i];
  }
  EXPECT_LT(halvings, hold_steps / 10)
      << "line-search halvings in " << hold_steps << " steps of the hold";
}

INSTANTIATE_TEST_SUITE_P(StudyCubes, Pinch, testing::Values(0.01, 0.06));

// The short step's iterations (SimParameters::short_step_excess, the default) are taken only in
// passes where no flesh touches anything, so that the pinches without a squeeze, whose pads'
// targets lie on the faces, are held and released with them within the slip issue #71 allows (1.3
// and 21 µm; measured 0.84 and 18.2 µm, as without the rule within 0.12 µm). Iterating where flesh
// touches as well lost the light one (slip 0.24 mm, no grip): a pinch that asks for no grip is held
// or lost by the solver's path (docs/simulator.md, "The short step's iterations").
TEST(PinchShortSteps, HoldTheCubesPinchedWithoutASqueeze) {
  for (const double cube : {0.01, 0.06}) {
    if (test::kUnderSanitizers && cube > 0.03) break;  // the same code as the light one
    const PinchScene scene = make_pinch_scene(cube, 1, 0.0, hand::HandShape{}.length);
    const PinchReport r = run_pinch(scene.model, scene.skeleton, scene.script);
    std::cout << "cube " << cube * 100 << " cm without a squeeze, short steps iterating: slip "
              << r.slip_mm << " mm, penetration " << r.max_penetration_mm << " mm, grip "
              << r.peak_grip_n << " N\n";
    EXPECT_TRUE(r.held) << "cube " << cube;
    EXPECT_TRUE(r.released) << "cube " << cube;
    EXPECT_LT(r.slip_mm, cube < 0.03 ? 0.0013 : 0.021) << "cube " << cube;
    EXPECT_LT(r.max_penetration_mm, cube < 0.03 ? 0.5 : 1.5) << "cube " << cube;
  }
}

// The heavy cube's pinch is placed by the pinch's rule (core/task/pinch_clearance.h): the pads
// on the faces and no other skin within 2 mm, so no finger rests on the top. Placed as the
// script first poses it, palm down with the fingers along the floor, the index lay across the
// top (its middle phalanx's target 14 mm inside) and pressed the cube into the floor with
// 133-143 N through the closing. The light cube's pinch keeps the script's pose.
TEST(PinchPlacement, TheHeavyCubesPinchLeavesItsTopFree) {
  const PinchScene scene = make_pinch_scene(0.06);
  const PinchScript& script = scene.script;
  EXPECT_TRUE(script.placed_by_rule);
  EXPECT_TRUE(script.pinch_meets_rule);
  EXPECT_GE(script.pinch_clearance, 0.002);
  EXPECT_LE(script.placement_pad_error, 0.001);
  double top = 0.0;  // N, the flesh on the cube's top face (+y of its frame)
  run_pinch(scene.model, scene.skeleton, script, {}, script.lift_start, [&](const HandSimState& s) {
    top = std::max(top, flesh_forces_on_cube_faces(scene.model, s)[3]);
  });
  EXPECT_LT(top, 5.0) << "N on the top before the lift";
  EXPECT_FALSE(make_pinch_scene(0.01).script.placed_by_rule);
}

// The pinch's rule counts the column under the cube as the cube (pinch_clearance.h): the hand
// comes down from above, so skin placed under the cube passed through it. A hand 9 cm under a
// cube's bottom is well off the cube and inside its column.
TEST(PinchPlacement, CountsTheColumnUnderTheCubeAsTheCube) {
  const PinchScene scene = make_pinch_scene(0.06);
  RigidPose cube;
  cube.position = scene.script.pinch.root_position + Eigen::Vector3d(0, 0.12, 0);
  const std::array<int, 2> no_pads = {-1, -1};
  const double off = skin_clearance(scene.skeleton, scene.model, scene.script.pinch, cube,
                                    scene.model.cube_half, no_pads)
                         .distance;
  const double placed = placement_clearance(scene.skeleton, scene.model, scene.script.pinch, cube,
                                            scene.model.cube_half, no_pads)
                            .distance;
  EXPECT_GT(off, 0.05);
  EXPECT_LT(placed, -0.01);
}

// The script run to the first second of the hold at each squeeze: the cube lifted and held,
// no slip, the skin (nodes and samples) within `skin_mm` of its faces.
void expect_held_at_each_squeeze(double cube, std::initializer_list<double> squeezes,
                                 double skin_mm) {
  for (const double squeeze : squeezes) {
    const PinchScene scene = make_pinch_scene(cube, 1, squeeze);
    const PinchReport r =
        run_pinch(scene.model, scene.skeleton, scene.script, {}, scene.script.lift_end + 1.0);
    EXPECT_TRUE(r.held) << "squeeze " << squeeze * 1000 << " mm: lifted " << r.lift * 100 << " cm";
    EXPECT_LT(r.slip_mm, 1.0) << "squeeze " << squeeze * 1000 << " mm";
    EXPECT_LT(r.max_penetration_mm, skin_mm) << "squeeze " << squeeze * 1000 << " mm";
  }
}

// The light cube's grasp does not hang on one setting: however hard the script squeezes (its
// pads' targets 2.5 to 3.5 mm inside the faces), the pads take the 1 cm cube, lift it and hold
// it (with a linear contact penalty of 20 kN/m, each of these five squeezes dropped it; only
// 3 mm, the default, held). The skin within 1 mm: where rounding differs (no fused multiply-add)
// a squeeze of 3.1 mm reached 0.67 mm, this build 0.22-0.39 mm for all five.
TEST(PinchRobustness, HoldsTheLightCubeForAnySqueeze) {
  if (test::kUnderSanitizers)  // the hardest, the deepest contact: the others' code
    expect_held_at_each_squeeze(0.01, {0.0035}, 1.0);
  else
    expect_held_at_each_squeeze(0.01, {0.0025, 0.0027, 0.0028, 0.0031, 0.0035}, 1.0);
}

// The heavy cube (108 g) too, its pads 20 mm under the top. With them 12 mm under it the
// fingertips hooked over the top edge, and once the skin no longer let the edge sink in between
// its nodes (2.2 mm with contact at the nodes alone), the cube turned out of the pads at the
// lift for 3.0, 3.2, 3.4 and 3.6 mm of fifteen squeezes from 2.5 to 4 mm.
TEST(PinchRobustness, HoldsTheHeavyCubeForAnySqueeze) {
  if (test::kUnderSanitizers)  // the hardest, the deepest contact: the others' code
    expect_held_at_each_squeeze(0.06, {0.0035}, 1.5);
  else
    expect_held_at_each_squeeze(0.06, {0.0025, 0.0027, 0.0028, 0.003, 0.0031, 0.0035}, 1.5);
}

// The skin, not only its nodes, keeps out of the cube: in the held light pinch no point of the
// flesh's boundary faces (their centroids, between the nodes) is more than 0.5 mm inside the
// cube. With contact at the nodes alone the cube's edges sank 1.7 mm into the skin between
// them while the nodes stayed within 0.1 mm.
TEST(PinchSkin, TheCubesEdgesDoNotSinkIntoTheSkinBetweenNodes) {
  auto deepest = [](int samples) {
    SimParameters parameters;
    parameters.skin_samples = samples;
    const PinchScene scene = make_pinch_scene(0.01, 1, 0.003, hand::HandShape{}.length, parameters);
    const std::vector<std::array<int, 3>> faces = boundary_faces(scene.flesh.tets.tets);
    double skin = 0.0;
    const PinchReport r = run_pinch(
        scene.model, scene.skeleton, scene.script, {}, scene.script.lift_end + 1.0,
        [&](const HandSimState& s) {
          if (s.time < scene.script.lift_end) return;
          const Eigen::Quaterniond to_cube = s.cube_pose.rotation.conjugate();
          for (const auto& f : faces) {
            const Eigen::Vector3d x =
                (s.node_position[std::size_t(f[0])] + s.node_position[std::size_t(f[1])] +
                 s.node_position[std::size_t(f[2])]) /
                3;
            const double d =
                box_proximity(scene.model.cube_half, to_cube * (x - s.cube_pose.position)).distance;
            skin = std::max(skin, -d);
          }
        });
    EXPECT_TRUE(r.held) << samples << " samples a face";
    return skin;
  };
  EXPECT_LT(deepest(1), 0.0005);
  EXPECT_GT(deepest(0), 0.001) << "nodes alone let the cube's edges into the skin";
}

// The same inputs and options give the same states, bit for bit, whether the per-tet work runs
// on one thread or is split over two (summed in a fixed order, whatever the timing). Under the
// sanitizers two threads alone, where timing could enter: one runs the same per-tet code unsplit.
TEST(PinchDeterminism, TheSameRunGivesTheSameStates) {
  const PinchScene scene = make_pinch_scene(SimParameters{}.cube_size);
  const HandSimModel& model = scene.model;
  const hand::Skeleton& skeleton = scene.skeleton;
  const PinchScript& script = scene.script;
  auto run = [&](int threads) {
    SimOptions options;
    options.threads = threads;
    std::vector<Eigen::Vector3d> trace;  // every 10th step's cube and first node
    int step = 0;
    run_pinch(model, skeleton, script, options, script.close_end + 0.1, [&](const HandSimState& s) {
      if (++step % 10 != 0) return;
      trace.push_back(s.cube_pose.position);
      trace.push_back(s.node_position.front());
    });
    trace.push_back(Eigen::Vector3d::Zero());
    return trace;
  };
  for (int threads : {1, 2}) {
    if (test::kUnderSanitizers && threads == 1) continue;
    const std::vector<Eigen::Vector3d> first = run(threads), second = run(threads);
    ASSERT_EQ(first.size(), second.size());
    for (std::size_t i = 0; i < first.size(); ++i)
      ASSERT_EQ(first[i], second[i]) << threads << " threads, sample " << i;
  }
}

// The script until the fingers have opened (its first phase, where tets cross the stiffening
// threshold every step and CG preconditioned by the previous step's factorisation fails),
// with the nodes where it ends.
struct Opening {
  PinchReport report;
  std::vector<Eigen::Vector3d> nodes;
};
Opening open_fingers(const PinchScene& scene, const SimOptions& options) {
  Opening o;
  o.report = run_pinch(scene.model, scene.skeleton, scene.script, options, scene.script.shape_end,
                       [&](const HandSimState& s) { o.nodes = s.node_position; });
  return o;
}

int total(const std::vector<int>& v) {
  return std::accumulate(v.begin(), v.end(), 0);
}

void print_iterations(const Opening& from, const Opening& to) {
  std::cout << "CG iterations " << total(from.report.linear_iterations) << " -> "
            << total(to.report.linear_iterations) << ", factorisations "
            << total(from.report.factorizations) << " -> " << total(to.report.factorizations)
            << "\n";
}

// How far apart two runs' nodes end (m).
double largest_gap(const Opening& a, const Opening& b) {
  EXPECT_EQ(a.nodes.size(), b.nodes.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < std::min(a.nodes.size(), b.nodes.size()); ++i)
    largest = std::max(largest, (a.nodes[i] - b.nodes[i]).norm());
  return largest;
}

// With direct_steps the steps after a failed CG factorise at once. They spend fewer CG
// iterations for the same factorisations and reach the same states, within the solver's
// tolerance.
TEST(PinchDirectSteps, SkipCgThatWouldFailAndReachTheSameStates) {
  const PinchScene scene = make_pinch_scene(SimParameters{}.cube_size);
  SimOptions options;
  options.refresh_steps = 0;
  options.halfway_gap = 0;  // every CG that fails takes all its iterations
  options.direct_steps = 0;
  const Opening cg = open_fingers(scene, options);
  options.direct_steps = 3;
  const Opening direct = open_fingers(scene, options);
  print_iterations(cg, direct);
  EXPECT_LT(total(direct.report.linear_iterations), total(cg.report.linear_iterations) / 2);
  EXPECT_LE(total(direct.report.factorizations), total(cg.report.factorizations) + 2);
  EXPECT_LT(largest_gap(cg, direct), 1e-5) << "m, the nodes after the fingers opened";
}

// CG that will fail is still far from converged halfway through its iterations: giving up
// there (halfway_gap) spends fewer CG iterations for no more factorisations, and the nodes end
// where they did.
TEST(PinchHalfwayGap, GivesUpOnCgThatWouldFail) {
  const PinchScene scene = make_pinch_scene(SimParameters{}.cube_size);
  SimOptions options;
  options.halfway_gap = 0;
  const Opening all = open_fingers(scene, options);
  options.halfway_gap = 1e3;
  const Opening halfway = open_fingers(scene, options);
  print_iterations(all, halfway);
  EXPECT_LT(total(halfway.report.linear_iterations), total(all.report.linear_iterations) * 9 / 10);
  EXPECT_LE(total(halfway.report.factorizations), total(all.report.factorizations));
  EXPECT_LT(largest_gap(all, halfway), 1e-5) << "m, the nodes after the fingers opened";
}

// Coming down over the cube, CG converges with an older factorisation, in two or three
// iterations a step as the matrix drifts; refresh_steps renews it after that many such steps.
TEST(PinchRefreshSteps, RenewADriftedPreconditioner) {
  const PinchScene scene = make_pinch_scene(SimParameters{}.cube_size);
  // The longest run of steps without a factorisation whose solves took two CG iterations or
  // more (one pass a step: its CG iterations are its first solve's).
  auto longest_drift = [&](int refresh_steps) {
    SimOptions options;
    options.refresh_steps = refresh_steps;
    const PinchReport r =
        run_pinch(scene.model, scene.skeleton, scene.script, options, scene.script.approach_end);
    int run = 0, longest = 0;
    for (std::size_t i = 0; i < r.linear_iterations.size(); ++i) {
      const bool drifted =
          r.newton_iterations[i] == 1 && r.factorizations[i] == 0 && r.linear_iterations[i] >= 2;
      run = drifted ? run + 1 : 0;
      longest = std::max(longest, run);
    }
    return longest;
  };
  EXPECT_GT(longest_drift(0), 8) << "steps: the approach drifts without renewal";
  EXPECT_LE(longest_drift(8), 8);
}

}  // namespace
}  // namespace handlab::sim
