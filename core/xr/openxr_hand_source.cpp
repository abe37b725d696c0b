#include "core/xr/openxr_hand_source.h"

#include <time.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "core/tracking/latest_frames.h"
#include "core/tracking/openxr_hand.h"
#include "core/xr/hand_trackers.h"
#include "core/xr/openxr_functions.h"

namespace handlab::xr {

struct OpenXrHandSource::Session {
  OpenXrFunctions xr;
  XrInstance instance = XR_NULL_HANDLE;
  XrSession session = XR_NULL_HANDLE;
  XrSpace space = XR_NULL_HANDLE;
  HandTrackers hands;
  std::string runtime;

  std::thread loop;
  std::atomic<bool> stop{false};
  tracking::LatestFrames frames;  // the loop's, newest first
  XrTime first_time = 0;
  std::int64_t located = 0;  // frames located so far

  ~Session() {
    stop = true;
    if (loop.joinable()) loop.join();
    hands.destroy(xr);
    if (space != XR_NULL_HANDLE) xr.destroy_space(space);
    if (session != XR_NULL_HANDLE) xr.destroy_session(session);
    if (instance != XR_NULL_HANDLE && xr.destroy_instance) xr.destroy_instance(instance);
  }

  // Session state changes: begun when ready, ended when stopping; false once it exits.
  bool handle_events(bool& session_running) {
    auto event = xr_struct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
    while (xr.poll_event(instance, &event) == XR_SUCCESS) {
      if (event.type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) {
        const auto& changed = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
        if (changed.state == XR_SESSION_STATE_READY) {
          auto begin = xr_struct<XrSessionBeginInfo>(XR_TYPE_SESSION_BEGIN_INFO);
          begin.primaryViewConfigurationType = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
          session_running = XR_SUCCEEDED(xr.begin_session(session, &begin));
        } else if (changed.state == XR_SESSION_STATE_STOPPING) {
          xr.end_session(session);
          session_running = false;
        } else if (changed.state == XR_SESSION_STATE_EXITING ||
                   changed.state == XR_SESSION_STATE_LOSS_PENDING) {
          return false;
        }
      } else if (event.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) {
        return false;
      }
      event = xr_struct<XrEventDataBuffer>(XR_TYPE_EVENT_DATA_BUFFER);
    }
    return true;
  }

  tracking::TrackedFrame locate(XrTime time) {
    tracking::TrackedFrame frame;
    if (first_time == 0) first_time = time;
    frame.timestamp = double(time - first_time) * 1e-9;
    frame.id = ++located;
    frame.hands = hands.locate(xr, space, time);
    return frame;
  }

  // A session with no graphics has no frame loop to pace it (xrWaitFrame predicts no display
  // time): the hands are located at the runtime's now, kRate times a second.
  static constexpr double kRate = 120.0;
  std::chrono::steady_clock::time_point next_tick{};

  void frame() {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_tick) std::this_thread::sleep_until(next_tick);
    next_tick =
        std::max(now, next_tick) + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                       std::chrono::duration<double>(1.0 / kRate));
    timespec monotonic{};
    clock_gettime(CLOCK_MONOTONIC, &monotonic);
    XrTime time = 0;
    if (XR_FAILED(xr.convert_time(instance, &monotonic, &time))) return;
    frames.publish(locate(time));
  }

  void run() {
    bool session_running = false, exit_requested = false;
    const auto give_up = [&] { return std::chrono::steady_clock::now(); };
    auto stop_deadline = give_up();
    while (true) {
      if (!handle_events(session_running)) break;
      if (stop && !exit_requested) {
        if (!session_running) break;
        xr.request_exit(session);
        exit_requested = true;
        stop_deadline = give_up() + std::chrono::seconds(1);
      }
      if (exit_requested && give_up() > stop_deadline) break;
      if (session_running)
        frame();
      else
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    frames.finish();
  }
};

namespace {

// The instance, system, headless session, LOCAL space and both hands' trackers; "" or why not.
std::string make_session(OpenXrHandSource::Session& s) {
  const OpenXrLoader& loader = OpenXrLoader::instance();
  if (!loader.available()) return loader.error();
  XrResult r = create_instance(
      loader, {"XR_EXT_hand_tracking", "XR_MND_headless", "XR_KHR_convert_timespec_time"},
      &s.instance);
  if (XR_FAILED(r))
    return "no OpenXR runtime with hand tracking, headless sessions and the monotonic clock "
           "(XR_EXT_hand_tracking, XR_MND_headless, XR_KHR_convert_timespec_time): " +
           result_name(r);
  if (!s.xr.load(loader, s.instance) || !s.xr.create_hand_tracker || !s.xr.convert_time)
    return "the OpenXR runtime lacks a function hands need";
  auto properties = xr_struct<XrInstanceProperties>(XR_TYPE_INSTANCE_PROPERTIES);
  if (XR_SUCCEEDED(s.xr.instance_properties(s.instance, &properties)))
    s.runtime = properties.runtimeName;
  auto system_info = xr_struct<XrSystemGetInfo>(XR_TYPE_SYSTEM_GET_INFO);
  system_info.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  if (XR_FAILED(r = s.xr.get_system(s.instance, &system_info, &system)))
    return "no headset: " + result_name(r);
  auto session_info = xr_struct<XrSessionCreateInfo>(XR_TYPE_SESSION_CREATE_INFO);
  session_info.systemId = system;
  if (XR_FAILED(r = s.xr.create_session(s.instance, &session_info, &s.session)))
    return "the OpenXR runtime made no session: " + result_name(r);
  auto space_info = xr_struct<XrReferenceSpaceCreateInfo>(XR_TYPE_REFERENCE_SPACE_CREATE_INFO);
  space_info.referenceSpaceType = XR_REFERENCE_SPACE_TYPE_LOCAL;
  space_info.poseInReferenceSpace.orientation.w = 1.0f;
  if (XR_FAILED(r = s.xr.create_space(s.session, &space_info, &s.space)))
    return "no LOCAL space: " + result_name(r);
  return s.hands.create(s.xr, s.session);
}

}  // namespace

std::unique_ptr<OpenXrHandSource> OpenXrHandSource::open(std::string& error,
                                                         std::chrono::milliseconds start_timeout) {
  auto s = std::make_unique<Session>();
  error = make_session(*s);
  if (!error.empty()) return nullptr;
  s->loop = std::thread([raw = s.get()] { raw->run(); });
  // Running once its first frame is there (left for the first next()).
  if (!s->frames.wait_for_frame(std::chrono::steady_clock::now() + start_timeout)) {
    error =
        "the OpenXR session did not start within " + std::to_string(start_timeout.count()) + " ms";
    return nullptr;
  }
  return std::unique_ptr<OpenXrHandSource>(new OpenXrHandSource(std::move(s)));
}

OpenXrHandSource::OpenXrHandSource(std::unique_ptr<Session> session)
    : session_(std::move(session)) {}

OpenXrHandSource::~OpenXrHandSource() = default;

std::optional<tracking::TrackedFrame> OpenXrHandSource::next() {
  return session_->frames.next();
}

bool OpenXrHandSource::wait_for_frame(std::chrono::steady_clock::time_point deadline) {
  return session_->frames.wait_for_frame(deadline);
}

bool OpenXrHandSource::ended() const {
  return session_->frames.ended();
}

std::string OpenXrHandSource::runtime_name() const {
  return session_->runtime;
}

namespace {

class SharedView : public tracking::LiveFrameSource {
 public:
  explicit SharedView(std::shared_ptr<tracking::LiveFrameSource> source)
      : source_(std::move(source)) {
    source_->next();
  }
  std::optional<tracking::TrackedFrame> next() override { return source_->next(); }
  bool ended() const override { return source_->ended(); }
  bool wait_for_frame(std::chrono::steady_clock::time_point deadline) override {
    return source_->wait_for_frame(deadline);
  }

 private:
  std::shared_ptr<tracking::LiveFrameSource> source_;
};

}  // namespace

std::unique_ptr<tracking::LiveFrameSource> view_of(
    std::shared_ptr<tracking::LiveFrameSource> source) {
  return std::make_unique<SharedView>(std::move(source));
}

}  // namespace handlab::xr
