// The participant's view in the headset while something else runs (a session): the display's
// frame loop on a thread of its own, drawing the newest scene it was given, and each frame's
// read-back images checked for the cube at the pixel each eye's projection puts it. The
// scene stands where a seated participant's table does (task_scene_camera).
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/render/draw_list.h"
#include "core/render/image.h"
#include "core/render/view_camera.h"
#include "core/xr/openxr_display.h"

namespace handlab::xr {

// An eye's camera in the LOCAL space as the task scene's: the scene 0.3 m below the head's
// start and 0.5 m ahead of it, a table before a seated participant.
render::ViewCamera task_scene_camera(const render::ViewCamera& local);

// The cube's colour (orange: far more red than blue) at the pixel where `camera` puts `centre`.
bool cube_at_its_pixel(const render::Image& image, const render::ViewCamera& camera,
                       const Eigen::Vector3f& centre);

struct HeadsetCounts {
  DisplayCounts loop;
  long shown = 0;              // frames drawn with a scene
  long cube_seen[2] = {0, 0};  // of those, the cube at its pixel in the left and right image
  long read_back_as_drawn = 0;
  // From a hand frame's time to the predicted display time of the first frame that showed
  // the scene made from it (ms), for scenes made from the headset's own hands.
  std::vector<double> latency_ms;
};

class HeadsetView {
 public:
  using EyeDrawer =
      std::function<render::Image(const render::DrawList& scene, const render::ViewCamera& camera)>;
  // Makes the eyes' drawer on the display's thread (an OpenGL context is a thread's).
  using DrawerFactory = std::function<EyeDrawer(int width, int height)>;
  // `state_changed` is called on the display's thread with the session's state ("focused",
  // "visible", "stopping", "exiting", ...) each time it changes, and "failed" where drawing
  // failed (error() says why) and the loop ended.
  // With `hands`, the headset's session also tracks the hands (OpenXrDisplay::HandSink).
  static std::unique_ptr<HeadsetView> open(std::string& error, DrawerFactory drawer,
                                           std::function<void(const std::string&)> state_changed,
                                           int max_eye_width = 0,
                                           OpenXrDisplay::HandSink hands = {});
  ~HeadsetView();  // closes
  // Ends the headset's session and waits for its loop to end; the counts and images stay.
  void close();

  // Starts the headset's loop with nothing to show yet (the hands it tracks then come).
  void start();
  // From any thread: the scene to show from now on, and where its cube's centre is. The
  // headset's loop starts with the first if it has not.
  // `hand_time`: the time of the headset's hand frame the scene was made from (s, as
  // DisplayFrame::time), NaN where it was not.
  void show(render::DrawList scene, const Eigen::Vector3f& cube_centre,
            double hand_time = std::numeric_limits<double>::quiet_NaN());
  // The loop ended: the runtime ended the session, or drawing failed (`error` says why).
  bool ended() const;
  std::string error() const;
  int eye_width() const;
  int eye_height() const;
  HeadsetCounts counts() const;
  std::string runtime_name() const;
  // The last frame shown: each eye's image as read back from its swapchain and its camera in
  // the task scene (not drawn before the first).
  DisplayFrame last_frame() const;

  struct Loop;  // the thread and what it shares (headset_view.cpp)

 private:
  explicit HeadsetView(std::unique_ptr<Loop> loop);
  std::unique_ptr<Loop> loop_;
};

}  // namespace handlab::xr
