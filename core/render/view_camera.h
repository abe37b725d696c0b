// A camera as its matrices: where it is, its view and projection (OpenGL's clip space). The
// orbit camera of a window and a headset's eyes (an OpenXR view: a pose and four field-of-view
// angles, asymmetric) are both drawn through it.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "core/render/orbit_camera.h"

namespace handlab::render {

struct ViewCamera {
  Eigen::Matrix4f view = Eigen::Matrix4f::Identity();
  Eigen::Matrix4f projection = Eigen::Matrix4f::Identity();
  Eigen::Vector3f eye = Eigen::Vector3f::Zero();
};

ViewCamera view_camera(const OrbitCamera& camera, float aspect);

// An eye at `pose` (the camera looks along its -z, +y up) seeing between the angles `left`,
// `right`, `down`, `up` (rad, left and down negative, as OpenXR's XrFovf has them).
ViewCamera eye_camera(const Eigen::Isometry3f& pose, float left, float right, float down, float up,
                      float near_plane = 0.01f, float far_plane = 20.0f);

// `world` in pixels (x right, y down) of a width x height picture; false behind the camera.
bool project_to_pixel(const ViewCamera& camera, int width, int height, const Eigen::Vector3f& world,
                      Eigen::Vector2f* pixel);

}  // namespace handlab::render
