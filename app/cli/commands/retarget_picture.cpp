#include "app/cli/commands/retarget_picture.h"

#include <stdexcept>

#include "core/hand/simulated_hand.h"
#include "core/hand/skin.h"
#include "core/render/hand_drawing.h"
#include "core/render/offscreen_context.h"
#include "core/render/render_mesh.h"
#include "core/render/scene_drawing.h"

namespace handlab::cli {
namespace {

constexpr double kPanelSpacing = 0.22;  // m between the three hands
constexpr double kPanelHeight = 0.12;   // m: palm centres above the floor
constexpr double kHalfPi = 1.57079632679489662;

void draw_sphere(render::DrawList& list, const Eigen::Vector3d& centre, double radius,
                 const Eigen::Vector4f& color) {
  static const auto sphere =
      std::make_shared<const render::RenderMesh>(render::make_capsule_mesh(1.0f, 0.0f, 16));
  Eigen::Matrix4f model = Eigen::Matrix4f::Identity();
  model.block<3, 3>(0, 0) = Eigen::Matrix3f::Identity() * float(radius);
  model.block<3, 1>(0, 3) = centre.cast<float>();
  list.items.push_back({sphere, model, color, render::Shading::kLit});
}

// The frame: the given one, or the first with the highest pinch strength.
const tracking::TrackedFrame* chosen_frame(const tracking::Recording& recording,
                                           tracking::Side side,
                                           std::optional<std::int64_t> frame_id) {
  const tracking::TrackedFrame* chosen = nullptr;
  for (const auto& f : recording.frames) {
    const tracking::TrackedHand* h = f.hand(side);
    if (!h) continue;
    if (frame_id ? f.id == *frame_id
                 : !chosen || h->pinch_strength > chosen->hand(side)->pinch_strength)
      chosen = &f;
  }
  if (!chosen) throw std::runtime_error("no such frame with that hand in the recording");
  return chosen;
}

// The three panels, seen from in front, into `path`.
void write_panels(const render::DrawList& list, const std::string& path) {
  render::OrbitCamera camera;
  camera.target = Eigen::Vector3f(0.0f, float(kPanelHeight), 0.0f);
  camera.distance = 0.55f;
  camera.pitch = 0.3f;
  camera.yaw = 0.0f;
  render::OffscreenRenderer renderer(1500, 600, 4);
  render::write_png(renderer.render(list, camera), path);
}

}  // namespace

std::int64_t write_retarget_picture(const tracking::Recording& recording, tracking::Side side,
                                    const hand::HandShape& shape,
                                    const retarget::Calibration& calibration,
                                    const tracking::TrackedHandFitter& fitter,
                                    std::optional<std::int64_t> frame_id, const std::string& path) {
  const tracking::TrackedFrame* chosen = chosen_frame(recording, side, frame_id);

  const hand::Skeleton simulated = hand::build_simulated_hand(shape);
  const hand::HandSkin skin = hand::build_skin(simulated, shape);
  retarget::Retargeter naive(retarget::Strategy::kNaive, simulated, calibration, fitter);
  retarget::Retargeter ours(retarget::Strategy::kOurs, simulated, calibration);
  tracking::TrackedHandFitter tracked_fit = fitter;
  retarget::RetargetResult naive_result, ours_result;
  hand::FitResult tracked_pose;
  // Every frame up to the chosen one, so that the warm starts are a session's.
  for (const auto& f : recording.frames) {
    const tracking::TrackedHand* h = f.hand(side);
    if (!h) continue;
    naive_result = naive.retarget(*h);
    ours_result = ours.retarget(*h);
    if (&f == chosen) {
      tracked_pose = tracked_fit.fit(*h);
      break;
    }
  }
  const tracking::TrackedHand& hand = *chosen->hand(side);

  // Each hand turned about the vertical through its palm centre so that its thumb-index
  // side faces the viewer, and moved to its panel.
  render::DrawList list;
  list.items.push_back(render::draw_task_scene({}, Eigen::Isometry3d::Identity()).items.front());
  const Eigen::Vector3d palm = calibration.tracker_to_scene * hand.palm_position;
  auto panel = [&](int i) {
    const double turn = side == tracking::Side::kRight ? kHalfPi : -kHalfPi;
    return Eigen::Translation3d(Eigen::Vector3d((i - 1) * kPanelSpacing, kPanelHeight, 0)) *
           Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitY()) * Eigen::Translation3d(-palm);
  };
  const Eigen::Vector4f thumb_color{0.95f, 0.25f, 0.25f, 1.0f},
      index_color{0.25f, 0.55f, 0.95f, 1.0f};
  // 1. The tracked hand, the participant's size: its fitted skeleton and its tips.
  render::draw_skeleton(list, tracked_fit.skeleton(), tracked_pose.pose,
                        panel(0) * calibration.tracker_to_scene, {0.35f, 0.6f, 0.85f, 1.0f},
                        {0.95f, 0.95f, 0.95f, 1.0f});
  draw_sphere(list, panel(0) * calibration.tracker_to_scene * hand.joints[0][4], 0.006,
              thumb_color);
  draw_sphere(list, panel(0) * calibration.tracker_to_scene * hand.joints[1][4], 0.006,
              index_color);
  // 2, 3. Naive and Ours: the simulated hand's skin, and the scaled tracked thumb and index
  // tips it should reach (the targets).
  const Eigen::Vector4f skin_color{0.86f, 0.67f, 0.56f, 1.0f};
  for (int i = 1; i <= 2; ++i) {
    const retarget::RetargetResult& r = i == 1 ? naive_result : ours_result;
    render::draw_skin(list, hand::skin_vertices(simulated, skin, r.pose), skin.surface.triangles,
                      panel(i), skin_color);
    draw_sphere(list, panel(i) * r.targets[0], 0.005, thumb_color);
    draw_sphere(list, panel(i) * r.targets[1], 0.005, index_color);
  }
  write_panels(list, path);
  return chosen->id;
}

}  // namespace handlab::cli
