#include "core/render/orbit_camera.h"

#include "core/render/view_camera.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

namespace handlab::render {

Eigen::Vector3f OrbitCamera::eye() const {
  const float c = std::cos(pitch);
  const Eigen::Vector3f offset(c * std::sin(yaw), std::sin(pitch), c * std::cos(yaw));
  return target + distance * offset;
}

Eigen::Matrix4f OrbitCamera::view() const {
  const Eigen::Vector3f e = eye();
  const Eigen::Vector3f f = (target - e).normalized();
  const Eigen::Vector3f s = f.cross(Eigen::Vector3f::UnitY()).normalized();
  const Eigen::Vector3f u = s.cross(f);
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(e);
  m(1, 3) = -u.dot(e);
  m(2, 3) = f.dot(e);
  return m;
}

Eigen::Matrix4f OrbitCamera::projection(float aspect) const {
  const float t = 1.0f / std::tan(0.5f * fov_y);
  Eigen::Matrix4f p = Eigen::Matrix4f::Zero();
  p(0, 0) = t / aspect;
  p(1, 1) = t;
  p(2, 2) = (far_plane + near_plane) / (near_plane - far_plane);
  p(2, 3) = 2.0f * far_plane * near_plane / (near_plane - far_plane);
  p(3, 2) = -1.0f;
  return p;
}

void OrbitCamera::orbit(float dx_pixels, float dy_pixels, float radians_per_pixel) {
  constexpr float kPitchLimit = 1.553f;  // 89 degrees
  yaw -= dx_pixels * radians_per_pixel;
  pitch = std::clamp(pitch + dy_pixels * radians_per_pixel, -kPitchLimit, kPitchLimit);
}

void OrbitCamera::zoom(float steps) {
  distance = std::clamp(distance * std::pow(0.9f, steps), 0.05f, 10.0f);
}

bool project_to_pixel(const OrbitCamera& camera, int width, int height,
                      const Eigen::Vector3f& world, Eigen::Vector2f* pixel) {
  return project_to_pixel(view_camera(camera, float(width) / float(height)), width, height, world,
                          pixel);
}

}  // namespace handlab::render
