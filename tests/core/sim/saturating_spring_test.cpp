#include "core/sim/saturating_spring.h"

#include <gtest/gtest.h>
#include <Eigen/LU>

namespace handlab::sim {
namespace saturating_spring_test {

// The force is the energy's gradient and the stiffness the force's, by central differences.
TEST(SaturatingSpring, ForceAndStiffnessAreTheEnergysDerivatives) {
  for (const double limit : {0.0, 0.5, 5.0}) {
    const Eigen::Vector3d d(0.003, -0.001, 0.002);
    const double k = 2000.0, e = 1e-7;
    const SpringResponse r = saturating_spring(k, limit, d);
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d step = Eigen::Vector3d::Zero();
      step(a) = e;
      const SpringResponse plus = saturating_spring(k, limit, d + step),
                           minus = saturating_spring(k, limit, d - step);
      EXPECT_NEAR((plus.energy - minus.energy) / (2 * e), r.force(a), 1e-6 * k * d.norm());
      EXPECT_TRUE(((plus.force - minus.force) / (2 * e)).isApprox(r.stiffness.col(a), 1e-6));
    }
  }
}

// Near rest it is the linear spring; stretched far, its force approaches the limit from below.
TEST(SaturatingSpring, IsLinearNearRestAndBoundedFarOut) {
  const double k = 2000.0, limit = 2.0;
  const Eigen::Vector3d small(1e-6, 0, 0), far(0.5, 0, 0);
  EXPECT_NEAR(saturating_spring(k, limit, small).force.x(), k * 1e-6, 1e-9);
  EXPECT_LT(saturating_spring(k, limit, far).force.norm(), limit);
  EXPECT_GT(saturating_spring(k, limit, far).force.norm(), 0.99 * limit);
  EXPECT_GT(saturating_spring(k, limit, far).stiffness.determinant(), 0.0);
}

}  // namespace saturating_spring_test
}  // namespace handlab::sim
