#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "core/render/orbit_camera.h"

namespace handlab::render {
namespace {

TEST(OrbitCamera, TargetProjectsToTheImageCentre) {
  OrbitCamera camera;
  Eigen::Vector2f pixel;
  ASSERT_TRUE(project_to_pixel(camera, 800, 600, camera.target, &pixel));
  EXPECT_NEAR(pixel.x(), 400.0f, 1e-3f);
  EXPECT_NEAR(pixel.y(), 300.0f, 1e-3f);
}

TEST(OrbitCamera, EyeIsAtTheDistanceAndViewIsRigid) {
  OrbitCamera camera;
  camera.orbit(37, -12);
  EXPECT_NEAR((camera.eye() - camera.target).norm(), camera.distance, 1e-5f);
  const Eigen::Matrix3f r = camera.view().block<3, 3>(0, 0);
  EXPECT_TRUE((r * r.transpose()).isIdentity(1e-5f));
  EXPECT_NEAR((camera.view() * camera.eye().homogeneous()).head<3>().norm(), 0.0f, 1e-5f);
}

TEST(OrbitCamera, PitchIsClampedAndZoomBounded) {
  OrbitCamera camera;
  camera.orbit(0, 1e6f);
  EXPECT_LT(camera.pitch, 1.5708f);
  camera.zoom(1000);
  EXPECT_FLOAT_EQ(camera.distance, 0.05f);
  camera.zoom(-1000);
  EXPECT_FLOAT_EQ(camera.distance, 10.0f);
}

TEST(OrbitCamera, PointBehindTheCameraDoesNotProject) {
  OrbitCamera camera;
  const Eigen::Vector3f behind = camera.eye() + (camera.eye() - camera.target);
  Eigen::Vector2f pixel;
  EXPECT_FALSE(project_to_pixel(camera, 800, 600, behind, &pixel));
}

}  // namespace
}  // namespace handlab::render
