#include "core/xr/headset_view.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>

namespace handlab::xr {

render::ViewCamera task_scene_camera(const render::ViewCamera& local) {
  const Eigen::Affine3f scene_in_local(Eigen::Translation3f(0.0f, -0.3f, -0.5f));
  render::ViewCamera camera = local;
  camera.view = local.view * scene_in_local.matrix();
  camera.eye = scene_in_local.inverse() * local.eye;
  return camera;
}

bool cube_at_its_pixel(const render::Image& image, const render::ViewCamera& camera,
                       const Eigen::Vector3f& centre) {
  Eigen::Vector2f p;
  if (!render::project_to_pixel(camera, image.width, image.height, centre, &p)) return false;
  const int x = int(p.x()), y = int(p.y());
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return false;
  const auto c = image.pixel(x, y);
  return c[0] > c[2] + 80;
}

struct HeadsetView::Loop {
  std::unique_ptr<OpenXrDisplay> display;
  DrawerFactory factory;
  std::function<void(const std::string&)> state_changed;
  std::thread thread;
  std::atomic<bool> stop{false}, ended{false};
  std::string error;  // under the mutex
  mutable std::mutex mutex;
  std::shared_ptr<const render::DrawList> scene;
  Eigen::Vector3f cube = Eigen::Vector3f::Zero();
  double hand_time = std::numeric_limits<double>::quiet_NaN();
  double hand_time_counted = std::numeric_limits<double>::quiet_NaN();
  HeadsetCounts counts;
  DisplayFrame last;

  ~Loop() { close(); }
  void start() {  // under the mutex
    if (!thread.joinable() && !stop) thread = std::thread([this] { run(); });
  }
  void close() {
    std::thread running;
    {
      std::lock_guard lock(mutex);
      stop = true;
      running = std::move(thread);
    }
    if (running.joinable()) running.join();
  }

  void tally(const DisplayFrame& f, const std::array<render::Image, 2>& drawn,
             const Eigen::Vector3f& centre, double shown_hand_time) {
    std::lock_guard lock(mutex);
    counts.loop = display->counts();
    if (!f.drawn) return;
    ++counts.shown;
    if (std::isfinite(shown_hand_time) && shown_hand_time != hand_time_counted) {
      counts.latency_ms.push_back(1000.0 * (f.time - shown_hand_time));
      hand_time_counted = shown_hand_time;
    }
    for (int e = 0; e < 2; ++e)
      counts.cube_seen[e] += cube_at_its_pixel(
          f.read_back[std::size_t(e)], task_scene_camera(f.cameras[std::size_t(e)]), centre);
    counts.read_back_as_drawn +=
        f.read_back[0].rgba == drawn[0].rgba && f.read_back[1].rgba == drawn[1].rgba;
    last = f;
    for (auto& camera : last.cameras) camera = task_scene_camera(camera);
  }

  // On the loop's thread: an exception there (the drawer's OpenGL context refused) ends the
  // loop and is kept, not thrown across the thread.
  void run() {
    bool failed = false;
    try {
      loop();
    } catch (const std::exception& e) {
      std::lock_guard lock(mutex);
      error = e.what();
      failed = true;
    }
    ended = true;
    if (failed && state_changed) state_changed("failed");
  }

  void loop() {
    const EyeDrawer drawer = factory(display->eye_width(), display->eye_height());
    std::array<render::Image, 2> drawn;
    std::string state;
    bool exit_requested = false;
    auto give_up = std::chrono::steady_clock::now();
    while (true) {
      std::shared_ptr<const render::DrawList> shown;
      Eigen::Vector3f centre;
      double shown_hand_time;
      {
        std::lock_guard lock(mutex);
        shown = scene;
        centre = cube;
        shown_hand_time = hand_time;
      }
      const long waits = display->counts().waits;
      DisplayFrame f;
      const bool going = display->frame(
          [&](int eye, const render::ViewCamera& camera, int, int) {
            return drawn[std::size_t(eye)] =
                       drawer(shown ? *shown : render::DrawList{}, task_scene_camera(camera));
          },
          &f);
      if (display->session_state() != state) {
        state = display->session_state();
        if (state_changed) state_changed(state);
      }
      if (!going) break;
      if (shown) tally(f, drawn, centre, shown_hand_time);
      if (stop && !exit_requested) {
        display->request_exit();
        exit_requested = true;
        give_up = std::chrono::steady_clock::now() + std::chrono::seconds(2);
      }
      if (exit_requested && std::chrono::steady_clock::now() > give_up) break;
      // Not running (not yet begun, or stopped): the runtime paces nothing.
      if (display->counts().waits == waits)
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
};

std::unique_ptr<HeadsetView> HeadsetView::open(
    std::string& error, DrawerFactory drawer, std::function<void(const std::string&)> state_changed,
    int max_eye_width, OpenXrDisplay::HandSink hands) {
  auto loop = std::make_unique<Loop>();
  loop->display = OpenXrDisplay::open(error, max_eye_width, std::move(hands));
  if (!loop->display) return nullptr;
  loop->factory = std::move(drawer);
  loop->state_changed = std::move(state_changed);
  return std::unique_ptr<HeadsetView>(new HeadsetView(std::move(loop)));
}

HeadsetView::HeadsetView(std::unique_ptr<Loop> loop) : loop_(std::move(loop)) {}
HeadsetView::~HeadsetView() = default;

void HeadsetView::close() {
  loop_->close();
}

void HeadsetView::show(render::DrawList scene, const Eigen::Vector3f& cube_centre,
                       double hand_time) {
  auto shared = std::make_shared<const render::DrawList>(std::move(scene));
  std::lock_guard lock(loop_->mutex);
  loop_->scene = std::move(shared);
  loop_->cube = cube_centre;
  loop_->hand_time = hand_time;
  loop_->start();
}

void HeadsetView::start() {
  std::lock_guard lock(loop_->mutex);
  loop_->start();
}

bool HeadsetView::ended() const {
  return loop_->ended;
}

std::string HeadsetView::error() const {
  std::lock_guard lock(loop_->mutex);
  return loop_->error;
}

int HeadsetView::eye_width() const {
  return loop_->display->eye_width();
}
int HeadsetView::eye_height() const {
  return loop_->display->eye_height();
}

HeadsetCounts HeadsetView::counts() const {
  std::lock_guard lock(loop_->mutex);
  return loop_->counts;
}

std::string HeadsetView::runtime_name() const {
  return loop_->display->runtime_name();
}

DisplayFrame HeadsetView::last_frame() const {
  std::lock_guard lock(loop_->mutex);
  return loop_->last;
}

}  // namespace handlab::xr
