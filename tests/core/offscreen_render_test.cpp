// OSMesa draws the task scene; pixels at the projections of known points have the colours
// of what stands there.
#include <cstdlib>
#include <filesystem>
#include <memory>

#include <gtest/gtest.h>

#include "core/render/image.h"
#include "core/render/offscreen_context.h"
#include "core/render/render_mesh.h"
#include "core/render/scene_drawing.h"
#include "core/render/sim_drawing.h"
#include "core/render/view_camera.h"
#include "core/task/pinch_scene.h"

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

// The ground (the floor and the zones on it) is drawn once and kept while the camera stays
// put; the rest is drawn over it clipped to the floor. Each frame must look as if drawn whole.
class KeptGround : public ::testing::Test {
 protected:
  // The task scene with the cube at `cube` and a red 4 cm box sunk halfway into zone B (as a
  // hand's fingers go through the floor: hand-floor contact is off).
  DrawList frame(const Eigen::Vector3d& cube) const {
    DrawList list = draw_task_scene(layout_, Eigen::Isometry3d(Eigen::Translation3d(cube)));
    static const auto box = std::make_shared<const RenderMesh>(make_box_mesh({1, 1, 1}));
    Eigen::Matrix4f model = Eigen::Matrix4f::Identity();
    model.block<3, 3>(0, 0) *= 0.04f;
    model.block<3, 1>(0, 3) = layout_.zone_b.cast<float>();
    list.items.push_back({box, model, {0.9f, 0.1f, 0.1f, 1.0f}, Shading::kLit});
    return list;
  }
  static DrawList whole(DrawList list) {
    for (DrawItem& item : list.items) item.ground = false;
    return list;
  }
  static int differing_pixels(const Image& a, const Image& b) {
    int count = 0;
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        for (int c = 0; c < 3; ++c)
          if (std::abs(int(a.pixel(x, y)[c]) - int(b.pixel(x, y)[c])) > 2) {
            ++count;
            break;
          }
    return count;
  }

  task::SceneLayout layout_;
  // Single-sampled: the ground is kept only where its picture can be copied in.
  OffscreenRenderer kept_{kWidth, kHeight, 1}, drawn_whole_{kWidth, kHeight, 1};
};

TEST_F(KeptGround, FramesLookAsIfDrawnWhole) {
  const Eigen::Vector3d at_a = task::cube_start_pose(layout_).translation();
  OrbitCamera camera;
  // Frames in a row: the ground's picture is drawn for the first, kept for the second (the
  // cube lifted and carried), drawn again when the camera turns, and not kept at all from
  // below the floor.
  struct Shot {
    Eigen::Vector3d cube;
    float yaw, pitch;
  };
  for (const Shot& shot :
       {Shot{at_a, 0.6f, 0.55f}, Shot{at_a + Eigen::Vector3d(0.1, 0.08, 0), 0.6f, 0.55f},
        Shot{at_a, 1.4f, 0.9f}, Shot{at_a, 1.4f, -0.3f}, Shot{at_a, 0.6f, 0.55f}}) {
    camera.yaw = shot.yaw;
    camera.pitch = shot.pitch;
    const DrawList list = frame(shot.cube);
    const Image kept = kept_.render(list, camera);
    const Image whole_picture = drawn_whole_.render(whole(list), camera);
    // Where the cube stands on zone A's paint (0.25 mm up), and where the red box meets the
    // floor, a pixel may fall the other way: clipped at the floor instead of hidden by it.
    EXPECT_LE(differing_pixels(kept, whole_picture), 20)
        << "yaw " << shot.yaw << ", pitch " << shot.pitch;
    if (shot.pitch < 0) continue;
    // The box's half under the floor stays hidden: its front face 1 cm down shows the floor.
    const Rgb under =
        at(kept, camera, layout_.zone_b.cast<float>() + Eigen::Vector3f(0.0f, -0.01f, 0.0201f));
    EXPECT_LT(under.r, under.g + 40) << "the sunk half shows through the floor";
    const Rgb over =
        at(kept, camera, layout_.zone_b.cast<float>() + Eigen::Vector3f(0.0f, 0.021f, 0.0f));
    EXPECT_GT(over.r, over.g + 80) << "the half above the floor is drawn";
  }
}

// A picture on the panel stands upright behind the zones, the right way round: its top rows
// (green) above, its left half (red) to the left as the participant sees it, its right
// (blue) to the right; and it hides nothing in front of it (the cube).
TEST(OffscreenPanel, ShowsItsPictureUprightBehindTheZones) {
  auto picture = std::make_shared<Image>();
  picture->width = 64;
  picture->height = 32;
  picture->rgba.resize(64 * 32 * 4);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = &picture->rgba[std::size_t(y * 64 + x) * 4];
      p[0] = y >= 8 && x < 32 ? 255 : 0;
      p[1] = y < 8 ? 255 : 0;
      p[2] = y >= 8 && x >= 32 ? 255 : 0;
      p[3] = 255;
    }
  task::SceneLayout layout;
  layout.cube_size = 0.06;
  DrawList list = draw_task_scene(layout, task::cube_start_pose(layout));
  draw_panel(list, layout, picture);
  // A seated participant's eye, 30 cm above the table and 50 cm before the zones.
  const ViewCamera camera = eye_camera(Eigen::Isometry3f(Eigen::Translation3f(0.0f, 0.3f, 0.5f)),
                                       -0.7f, 0.7f, -0.6f, 0.6f);
  OffscreenRenderer renderer(kWidth, kHeight, 1);
  const Image image = renderer.render(list, camera);
  auto seen = [&](float x, float y, float z) {
    Eigen::Vector2f p;
    EXPECT_TRUE(project_to_pixel(camera, kWidth, kHeight, {x, y, z}, &p));
    const auto px = image.pixel(int(p.x()), int(p.y()));
    return Rgb{px[0], px[1], px[2]};
  };
  // The panel: 40 cm wide, 20 cm high (the picture's 2:1), from 8 cm up, 25 cm behind.
  const Rgb top = seen(0.0f, 0.27f, -0.25f), left = seen(-0.1f, 0.14f, -0.25f),
            right = seen(0.1f, 0.14f, -0.25f);
  EXPECT_GT(top.g, 200);
  EXPECT_LT(top.r + top.b, 40);
  EXPECT_GT(left.r, 200);
  EXPECT_LT(left.g + left.b, 40);
  EXPECT_GT(right.b, 200);
  EXPECT_LT(right.r + right.g, 40);
  const Rgb beside = seen(0.25f, 0.14f, -0.25f);  // past its right edge: the background
  EXPECT_LT(beside.b, 100);
  const Rgb cube = seen(float(layout.zone_a.x()), 0.03f, float(layout.zone_a.z()));
  EXPECT_GT(cube.r, cube.b + 80) << "the cube before the panel";
}

TEST(OffscreenRenderer, RejectsAbsurdSizes) {
  EXPECT_THROW(OffscreenRenderer(0, 10), std::runtime_error);
}

}  // namespace
}  // namespace handlab::render
