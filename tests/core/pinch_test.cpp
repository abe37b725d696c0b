// The study hand pinches each of the study's cubes between thumb and index on the scripted
// pinch-and-lift (core/sim/pinch_script.h): it lifts it 10 cm and holds it 5 s without letting
// it slip or sink into the flesh, and opening the fingers lets it fall back to the floor.
#include <iostream>

#include <gtest/gtest.h>

#include "core/sim/pinch_scene.h"

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
  EXPECT_LT(r.max_penetration_mm, 0.5);
  EXPECT_TRUE(r.released) << "opening the fingers should drop it back on the floor";
  EXPECT_LT(highest - script.cube_centre.y(), script.lift_height + 0.01) << "m: flung upwards";
}

INSTANTIATE_TEST_SUITE_P(StudyCubes, Pinch, testing::Values(0.01, 0.06));

// The same inputs and options give the same states, bit for bit, whether the per-tet work runs
// on one thread or is split over two (summed in a fixed order, whatever the timing).
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
    const std::vector<Eigen::Vector3d> first = run(threads), second = run(threads);
    ASSERT_EQ(first.size(), second.size());
    for (std::size_t i = 0; i < first.size(); ++i)
      ASSERT_EQ(first[i], second[i]) << threads << " threads, sample " << i;
  }
}

// Conjugate gradients multiply by the Newton matrix term by term, never assembling it; through
// the approach, the closing (contacts appear, stick and slip) and the start of the lift, every
// such product and the diagonal the preconditioner's test uses equal the assembled matrix's.
TEST(PinchNewtonMatrix, ProductsTermByTermEqualTheAssembledMatrix) {
  const PinchScene scene = make_pinch_scene(SimParameters{}.cube_size);
  const HandSimModel& model = scene.model;
  const hand::Skeleton& skeleton = scene.skeleton;
  const PinchScript& script = scene.script;
  SimOptions options;
  options.check_products = true;
  PinchReport r;
  EXPECT_NO_THROW(r = run_pinch(model, skeleton, script, options, script.lift_start + 0.1));
  int products = 0, touching = 0;  // a direct solve counts one linear iteration, no product
  for (std::size_t i = 0; i < r.linear_iterations.size(); ++i) {
    products += r.linear_iterations[i] - r.factorizations[i];
    if (r.contacts[i] > 0) ++touching;
  }
  EXPECT_GT(products, 1000) << "products compared";
  EXPECT_GT(touching, 100) << "steps with contacts";
}

}  // namespace
}  // namespace handlab::sim
