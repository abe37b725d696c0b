// A headset as the participant's display: an OpenXR session on Vulkan (XR_KHR_vulkan_enable2),
// a swapchain an eye, paced by the runtime's frame loop (xrWaitFrame, xrBeginFrame,
// xrEndFrame). Each eye is drawn by the caller (handlab's OpenGL drawing, offscreen) with the
// camera of the runtime's view for that eye, copied into the eye's swapchain image, and read
// back from it before the image is released, so that what the headset was given can be
// checked and kept.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <string>

#include "core/render/image.h"
#include "core/render/view_camera.h"
#include "core/tracking/tracked_frame.h"

namespace handlab::xr {

// One frame as it went to the headset.
struct DisplayFrame {
  bool drawn = false;  // the runtime asked for the frame to be drawn (shouldRender)
  std::array<render::ViewCamera, 2> cameras;  // the eyes', in the LOCAL space
  std::array<render::Image, 2> read_back;     // each eye's swapchain image as it was released
  double time = 0.0;                          // predicted display time (s, from the first)
};

// How the frame loop went: every xrWaitFrame followed by one xrBeginFrame and one xrEndFrame.
struct DisplayCounts {
  long waits = 0, begins = 0, ends = 0, drawn = 0;
};

class OpenXrDisplay {
 public:
  struct Session;  // the OpenXR and Vulkan objects (openxr_display.cpp)

  // The hands the headset's session tracks, located at each frame's predicted display time
  // (timestamps in s from the first frame's, as DisplayFrame::time), on the frame's thread.
  using HandSink = std::function<void(tracking::TrackedFrame)>;

  // A session on the runtime's headset (it begins in frame() once the runtime is ready);
  // nullptr with `error` saying why. Eyes wider than `max_eye_width` pixels (0: as the runtime
  // recommends) are drawn at that width. With `hands`, the session also tracks both hands
  // (XR_EXT_hand_tracking) and gives each frame's to it.
  static std::unique_ptr<OpenXrDisplay> open(std::string& error, int max_eye_width = 0,
                                             HandSink hands = {});
  ~OpenXrDisplay();

  using EyeDrawing = std::function<render::Image(int eye, const render::ViewCamera& camera,
                                                 int width, int height)>;
  // One frame of the runtime's loop; `draw` draws each eye when the runtime asks for it. False
  // once the session has ended (the runtime stopped it or was lost).
  bool frame(const EyeDrawing& draw, DisplayFrame* out = nullptr);
  // Asks the runtime to end the session; frame() then returns false once it has.
  void request_exit();

  int eye_width() const;
  int eye_height() const;
  std::string runtime_name() const;
  std::string session_state() const;  // "focused", "visible", "stopping", ...
  DisplayCounts counts() const;

 private:
  explicit OpenXrDisplay(std::unique_ptr<Session> session);
  std::unique_ptr<Session> session_;
};

}  // namespace handlab::xr
