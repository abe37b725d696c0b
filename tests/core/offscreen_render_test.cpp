// OSMesa draws the task scene; pixels at the projections of known points have the colours
// of what stands there.
#include <filesystem>

#include <gtest/gtest.h>

#include "core/render/image.h"
#include "core/render/offscreen_context.h"
#include "core/render/scene_drawing.h"
#include "core/render/sim_drawing.h"
#include "core/sim/pinch_scene.h"

namespace handlab::render {
namespace {

constexpr int kWidth = 400, kHeight = 300;

struct Rgb {
  int r, g, b;
};

Rgb at(const Image& image, const OrbitCamera& camera, const Eigen::Vector3f& world) {
  Eigen::Vector2f p;
  EXPECT_TRUE(project_to_pixel(camera, image.width, image.height, world, &p));
  const auto px = image.pixel(int(p.x()), int(p.y()));
  return {px[0], px[1], px[2]};
}

class OffscreenRender : public ::testing::Test {
 protected:
  void SetUp() override {
    layout_.cube_size = 0.06;
    image_ = renderer_.render(draw_task_scene(layout_, task::cube_start_pose(layout_)), camera_);
  }
  task::SceneLayout layout_;
  OrbitCamera camera_;
  OffscreenRenderer renderer_{kWidth, kHeight, 4};
  Image image_;
};

TEST_F(OffscreenRender, BackgroundIsTheClearColour) {
  // The top-left corner looks over the floor's far edge, into the background.
  const auto px = image_.pixel(2, 2);
  const DrawList list;
  EXPECT_NEAR(px[0], 255 * list.background.x(), 1.5);
  EXPECT_NEAR(px[1], 255 * list.background.y(), 1.5);
  EXPECT_NEAR(px[2], 255 * list.background.z(), 1.5);
}

TEST_F(OffscreenRender, CubeIsOrange) {
  // The centre of the cube's top face.
  const Eigen::Vector3f top = layout_.zone_a.cast<float>() + Eigen::Vector3f(0, 0.06f, 0);
  const Rgb c = at(image_, camera_, top);
  EXPECT_GT(c.r, 150);
  EXPECT_GT(c.r, c.g + 60);
  EXPECT_GT(c.g, c.b + 30);
}

TEST_F(OffscreenRender, FloorIsLitGrey) {
  const Rgb c = at(image_, camera_, Eigen::Vector3f(0.0f, 0.0f, 0.2f));
  EXPECT_GT(c.r, 120);
  EXPECT_NEAR(c.r, c.g, 12);
  EXPECT_NEAR(c.g, c.b, 12);
}

TEST_F(OffscreenRender, ZonesShowTheirColours) {
  // A point on each zone's outline.
  const float edge = 0.5f * float(layout_.zone_size) - 0.004f;
  const Rgb a = at(image_, camera_, layout_.zone_a.cast<float>() + Eigen::Vector3f(0, 0, edge));
  const Rgb b = at(image_, camera_, layout_.zone_b.cast<float>() + Eigen::Vector3f(0, 0, edge));
  EXPECT_GT(a.g, a.r + 40);
  EXPECT_GT(a.g, a.b + 40);
  EXPECT_GT(b.b, b.r + 60);
  EXPECT_GT(b.b, b.g + 20);
}

TEST_F(OffscreenRender, PngRoundTripKeepsTheSize) {
  const std::string path = std::string(HANDLAB_TEST_TMP) + "/scene.png";
  write_png(image_, path);
  int w = 0, h = 0;
  ASSERT_TRUE(read_png_size(path, &w, &h));
  EXPECT_EQ(w, kWidth);
  EXPECT_EQ(h, kHeight);
  EXPECT_LT(std::filesystem::file_size(path), image_.rgba.size() / 4);  // compressed
}

// A simulator state: the cube where the state has it (lifted here), the flesh's skin where its
// nodes are, and contact points over everything when asked: a flesh node inside the cube
// shows red through the cube's face, a corner on the floor blue.
TEST(OffscreenSimState, DrawsTheCubeTheSkinAndTheContactPoints) {
  const sim::PinchScene scene = sim::make_pinch_scene(0.06);
  sim::HandSimState state = scene.start();
  state.cube_pose.position += Eigen::Vector3d(0, 0.02, 0);
  const Eigen::Vector3d centre = state.cube_pose.position;
  state.node_position[0] = centre;  // as if pushed into the cube
  state.node_cube.push_back({0, Eigen::Vector3d::Zero()});
  state.corner_floor.push_back({1, Eigen::Vector3d::Zero()});  // +x, -y, -z
  task::SceneLayout layout;
  layout.cube_size = 0.06;
  OrbitCamera camera;
  camera.target = centre.cast<float>();
  camera.distance = 0.5f;
  OffscreenRenderer renderer(kWidth, kHeight, 4);
  SimDrawStyle style;
  const Image plain =
      renderer.render(draw_sim_state(layout, scene.flesh, scene.model, state, style), camera);
  style.contacts = true;
  const Image marked =
      renderer.render(draw_sim_state(layout, scene.flesh, scene.model, state, style), camera);
  const Rgb cube = at(plain, camera, centre.cast<float>());
  EXPECT_GT(cube.r, cube.g + 60) << "the lifted cube is drawn where the state has it";
  EXPECT_GT(cube.g, cube.b + 30);
  const Rgb inside = at(marked, camera, centre.cast<float>());
  EXPECT_GT(inside.r, 180);
  EXPECT_LT(inside.g, 60) << "the contact point inside the cube shows red";
  const Rgb corner =
      at(marked, camera, sim::cube_corner(scene.model, state.cube_pose, 1).cast<float>());
  EXPECT_GT(corner.b, corner.r + 80) << "the corner's contact point shows blue";
  // The skin: the middle of the flesh's nodes is on the hand, whose colour differs from the
  // background's and the floor's.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t n = 1; n < state.node_position.size(); ++n) mean += state.node_position[n];
  mean /= double(state.node_position.size() - 1);
  camera.target = mean.cast<float>();
  const Image hand =
      renderer.render(draw_sim_state(layout, scene.flesh, scene.model, state, style), camera);
  const auto px = hand.pixel(kWidth / 2, kHeight / 2);
  EXPECT_GT(px[0], px[2] + 40) << "skin colour at the hand's middle";
}

TEST(OffscreenRenderer, RejectsAbsurdSizes) {
  EXPECT_THROW(OffscreenRenderer(0, 10), std::runtime_error);
}

}  // namespace
}  // namespace handlab::render
