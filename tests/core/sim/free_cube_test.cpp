// A cube that no flesh touches, moving, is stepped alone in substeps (core/sim/free_cube.h):
// beside a body of flesh, the half-gram 1 cm cube kicked along the floor and spun over its
// edges, as fingers that let go unevenly flick it, comes to rest within 0.3 s, slides no
// further than its energy allows (E0 / (mu m g), plus 2 mm) and rises no higher (E0 / (m g),
// plus 0.5 mm). Stepped with the flesh at 1/120 s, it hopped and skated (`sim settle`: up to
// 187 mm beyond that slide, at rest after 0.64 s p90).
#include <gtest/gtest.h>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/task/cube_settle.h"
#include "tests/core/sim/lone_cube.h"

namespace handlab::sim {
namespace {

TEST(FreeCube, SettlesAsItsEnergyAllowsBesideFlesh) {
  SimParameters p;
  p.cube_size = 0.01;
  const HandSimModel model = lone_cube_model(p);  // beside one tet of flesh a metre away
  RigidPose cube;
  cube.position = Eigen::Vector3d(0, p.cube_size / 2, 0);
  const double weight = p.cube_density * 1e-6 * 9.81;
  for (double speed : {0.02, 0.05, 0.1, 0.2, 0.4})
    for (double spin : {0.0, 1.0, 2.0, 5.0, 10.0, 15.0, 20.0, 30.0}) {
      const CubeSettleReport r =
          settle_cube(model, lone_cube_state(model, cube), {speed, spin}, {}, 1.5);
      EXPECT_GE(r.rest_time, 0.0) << speed << " m/s, " << spin << " rad/s";
      EXPECT_LE(r.rest_time, 0.3) << speed << " m/s, " << spin << " rad/s";
      EXPECT_LE(r.travelled, r.slide_bound + 0.002) << speed << " m/s, " << spin << " rad/s";
      EXPECT_LE(r.highest_rise, r.start_energy / weight + 5e-4)
          << speed << " m/s, " << spin << " rad/s";
    }
}

}  // namespace
}  // namespace handlab::sim
