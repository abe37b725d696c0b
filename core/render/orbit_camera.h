// A camera that orbits a target point: yaw about the world up axis (+y), pitch above the
// horizon, distance from the target. Mouse drags orbit, the wheel zooms.
#pragma once

#include <Eigen/Core>

namespace handlab::render {

struct OrbitCamera {
  Eigen::Vector3f target{0.0f, 0.05f, 0.0f};
  float yaw = 0.6f;          // rad, about +y; 0 looks along -z
  float pitch = 0.55f;       // rad above the horizon
  float distance = 0.75f;    // m
  float fov_y = 0.8f;        // rad
  float near_plane = 0.01f;  // m
  float far_plane = 20.0f;   // m

  Eigen::Vector3f eye() const;
  Eigen::Matrix4f view() const;
  Eigen::Matrix4f projection(float aspect) const;

  // Drag by (dx, dy) pixels: 1 pixel turns by `radians_per_pixel`; pitch stays within ±89°.
  void orbit(float dx_pixels, float dy_pixels, float radians_per_pixel = 0.01f);
  // Wheel steps (positive zooms in); each step scales the distance by 0.9, within [0.05, 10] m.
  void zoom(float steps);
};

// Maps a world point to window pixel coordinates (x right, y down) for a width x height image.
// Returns false when the point is behind the camera.
bool project_to_pixel(const OrbitCamera& camera, int width, int height,
                      const Eigen::Vector3f& world, Eigen::Vector2f* pixel);

}  // namespace handlab::render
