#include "core/sim/saturating_damper.h"

#include <gtest/gtest.h>
#include <Eigen/LU>

namespace handlab::sim {
namespace saturating_damper_test {

// The force is the step energy's gradient in the displacement and the stiffness the force's, by
// central differences.
TEST(SaturatingDamper, ForceAndStiffnessAreTheEnergysDerivatives) {
  const double c = 50.0, h = 1.0 / 120, e = 1e-9;
  for (const double v0 : {0.0, 0.07, 1.0}) {
    const Eigen::Vector3d d(0.0003, -0.0001, 0.0002);
    const SpringResponse r = saturating_damper(c, v0, h, d);
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d step = Eigen::Vector3d::Zero();
      step(a) = e;
      const SpringResponse plus = saturating_damper(c, v0, h, d + step),
                           minus = saturating_damper(c, v0, h, d - step);
      EXPECT_NEAR((plus.energy - minus.energy) / (2 * e), r.force(a), 1e-6 * r.force.norm());
      EXPECT_TRUE(((plus.force - minus.force) / (2 * e)).isApprox(r.stiffness.col(a), 1e-6));
    }
  }
}

// Slow, it is the linear damper c v; fast, its force approaches c v0 from below, and its
// stiffness stays positive definite.
TEST(SaturatingDamper, IsLinearWhenSlowAndBoundedWhenFast) {
  const double c = 50.0, v0 = 0.07, h = 1.0 / 120;
  const Eigen::Vector3d slow(1e-9, 0, 0), fast(0.05, 0.02, 0);  // 0.12 mm/s, 6.5 m/s
  EXPECT_NEAR(saturating_damper(c, v0, h, slow).force.x(), c * 1e-9 / h, 1e-5 * c * 1e-9 / h);
  EXPECT_NEAR(saturating_damper(c, 0.0, h, fast).force.x(), c * 0.05 / h, 1e-9);
  const SpringResponse r = saturating_damper(c, v0, h, fast);
  EXPECT_LT(r.force.norm(), c * v0);
  EXPECT_GT(r.force.norm(), 0.98 * c * v0);
  EXPECT_TRUE(r.force.normalized().isApprox(fast.normalized()));
  EXPECT_GT(r.stiffness.determinant(), 0.0);
  EXPECT_EQ(saturating_damper(c, v0, h, Eigen::Vector3d::Zero()).force, Eigen::Vector3d::Zero());
}

}  // namespace saturating_damper_test
}  // namespace handlab::sim
