#include <cmath>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "core/render/orbit_camera.h"
#include "core/render/view_camera.h"

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

// A headset's eye: a pose and OpenXR's four angles. Along the eye's -z a point lands where the
// angles put the axis: the centre for a symmetric field, off it by tan's share for another.
TEST(ViewCamera, AnEyesFieldOfViewPutsPointsWhereItsAnglesSay) {
  Eigen::Isometry3f pose = Eigen::Isometry3f::Identity();
  pose.translation() = Eigen::Vector3f(0.1f, 1.5f, 0.0f);
  const ViewCamera symmetric = eye_camera(pose, -0.7f, 0.7f, -0.6f, 0.6f);
  Eigen::Vector2f pixel;
  ASSERT_TRUE(project_to_pixel(symmetric, 400, 300, Eigen::Vector3f(0.1f, 1.5f, -2.0f), &pixel));
  EXPECT_NEAR(pixel.x(), 200.0f, 1e-3f);
  EXPECT_NEAR(pixel.y(), 150.0f, 1e-3f);
  // The inner edge narrower than the outer, as a left eye's: the axis right of the centre.
  const float left = -0.9f, right = 0.5f, down = -0.6f, up = 0.4f;
  const ViewCamera asymmetric = eye_camera(pose, left, right, down, up);
  ASSERT_TRUE(project_to_pixel(asymmetric, 400, 300, Eigen::Vector3f(0.1f, 1.5f, -2.0f), &pixel));
  EXPECT_NEAR(pixel.x(), 400.0f * -std::tan(left) / (std::tan(right) - std::tan(left)), 1e-2f);
  EXPECT_NEAR(pixel.y(), 300.0f * std::tan(up) / (std::tan(up) - std::tan(down)), 1e-2f);
  // A point on the field's right edge lands on the picture's right edge; turned, the eye too.
  ASSERT_TRUE(project_to_pixel(
      asymmetric, 400, 300, Eigen::Vector3f(0.1f + 2.0f * std::tan(right), 1.5f, -2.0f), &pixel));
  EXPECT_NEAR(pixel.x(), 400.0f, 1e-2f);
  pose.linear() = Eigen::AngleAxisf(0.5f, Eigen::Vector3f::UnitY()).toRotationMatrix();
  const Eigen::Vector3f ahead = pose * Eigen::Vector3f(0.0f, 0.0f, -3.0f);
  ASSERT_TRUE(
      project_to_pixel(eye_camera(pose, -0.7f, 0.7f, -0.6f, 0.6f), 400, 300, ahead, &pixel));
  EXPECT_NEAR(pixel.x(), 200.0f, 1e-2f);
}

// The orbit camera's matrices as a view camera: the same pixel either way.
TEST(ViewCamera, AnOrbitCameraProjectsAsItsViewCamera) {
  OrbitCamera camera;
  const Eigen::Vector3f point(0.05f, 0.02f, -0.03f);
  Eigen::Vector2f a, b;
  ASSERT_TRUE(project_to_pixel(camera, 800, 600, point, &a));
  ASSERT_TRUE(project_to_pixel(view_camera(camera, 800.0f / 600.0f), 800, 600, point, &b));
  EXPECT_EQ(a, b);
}

}  // namespace
}  // namespace handlab::render
