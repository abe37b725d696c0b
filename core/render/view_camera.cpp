#include "core/render/view_camera.h"

#include <cmath>

namespace handlab::render {

ViewCamera view_camera(const OrbitCamera& camera, float aspect) {
  return {camera.view(), camera.projection(aspect), camera.eye()};
}

ViewCamera eye_camera(const Eigen::Isometry3f& pose, float left, float right, float down, float up,
                      float near_plane, float far_plane) {
  ViewCamera c;
  c.view = pose.inverse().matrix();
  c.eye = pose.translation();
  const float l = std::tan(left), r = std::tan(right), b = std::tan(down), t = std::tan(up);
  Eigen::Matrix4f& p = c.projection;
  p.setZero();
  p(0, 0) = 2.0f / (r - l);
  p(0, 2) = (r + l) / (r - l);
  p(1, 1) = 2.0f / (t - b);
  p(1, 2) = (t + b) / (t - b);
  p(2, 2) = (far_plane + near_plane) / (near_plane - far_plane);
  p(2, 3) = 2.0f * far_plane * near_plane / (near_plane - far_plane);
  p(3, 2) = -1.0f;
  return c;
}

bool project_to_pixel(const ViewCamera& camera, int width, int height, const Eigen::Vector3f& world,
                      Eigen::Vector2f* pixel) {
  const Eigen::Vector4f clip = camera.projection * camera.view * world.homogeneous();
  if (clip.w() <= 0.0f) return false;
  const Eigen::Vector2f ndc = clip.head<2>() / clip.w();
  *pixel = Eigen::Vector2f(0.5f * (ndc.x() + 1.0f) * width, 0.5f * (1.0f - ndc.y()) * height);
  return true;
}

}  // namespace handlab::render
