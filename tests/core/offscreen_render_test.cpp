// OSMesa draws the task scene; pixels at the projections of known points have the colours
// of what stands there.
#include <filesystem>

#include <gtest/gtest.h>

#include "core/render/image.h"
#include "core/render/offscreen_context.h"
#include "core/render/scene_drawing.h"

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

TEST(OffscreenRenderer, RejectsAbsurdSizes) {
  EXPECT_THROW(OffscreenRenderer(0, 10), std::runtime_error);
}

}  // namespace
}  // namespace handlab::render
