#include "app/gui/pinch_simulation.h"

#include <chrono>
#include <optional>

#include "core/render/sim_drawing.h"
#include "core/sim/hand_simulator.h"
#include "core/task/pinch_scene.h"

namespace handlab::gui {

// What the worker publishes and the GUI thread reads, under the mutex.
struct PinchSimulation::Shared {
  mutable std::mutex mutex;
  std::optional<sim::PinchScene> scene;  // set once, before the first state
  std::optional<sim::HandSimState> state;
  Progress progress;
  QString error;
};

PinchSimulation::PinchSimulation(double cube_size, double until, QObject* parent)
    : QObject(parent), shared_(std::make_unique<Shared>()) {
  worker_ = std::thread([this, cube_size, until] { run(cube_size, until); });
}

PinchSimulation::~PinchSimulation() {
  stop();
  if (worker_.joinable()) worker_.join();
}

void PinchSimulation::stop() {
  stop_ = true;
}

void PinchSimulation::run(double cube_size, double until) {
  try {
    sim::PinchScene built = sim::make_pinch_scene(cube_size);
    sim::HandSimState state = built.start();
    {
      std::lock_guard lock(shared_->mutex);
      shared_->scene = std::move(built);
      shared_->state = state;
    }
    // The scene is not touched again by any writer: read it without the lock from here on.
    const sim::PinchScene& scene = *shared_->scene;
    sim::HandSimulator simulator(scene.model);
    const double h = scene.model.parameters.time_step;
    const double end = until > 0 ? std::min(until, scene.script.end) : scene.script.end;
    const int steps = int(std::ceil(end / h - 1e-9));
    for (int i = 0; i < steps && !stop_; ++i) {
      const auto targets =
          sim::bone_targets(scene.model, scene.skeleton, scene.script.target((i + 1) * h));
      const auto begin = std::chrono::steady_clock::now();
      const sim::SimStepReport report = simulator.step(state, targets);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin)
              .count();
      {
        std::lock_guard lock(shared_->mutex);
        shared_->state = state;
        shared_->progress = {state.time, ms, report.contacts};
      }
      // One notification pending at a time: the view draws the newest state, not every one.
      if (!pending_.exchange(true))
        QMetaObject::invokeMethod(
            this,
            [this] {
              pending_ = false;
              emit advanced();
            },
            Qt::QueuedConnection);
    }
  } catch (const std::exception& e) {
    std::lock_guard lock(shared_->mutex);
    shared_->error = QString::fromUtf8(e.what());
  }
  finished_ = true;
  QMetaObject::invokeMethod(
      this, [this] { emit done(); }, Qt::QueuedConnection);
}

bool PinchSimulation::has_state() const {
  std::lock_guard lock(shared_->mutex);
  return shared_->state.has_value();
}

render::DrawList PinchSimulation::draw(const task::SceneLayout& layout, bool contacts) const {
  std::lock_guard lock(shared_->mutex);
  if (!shared_->state) return {};
  const sim::PinchScene& scene = *shared_->scene;
  // The cube starts in zone A; zone B lies beyond, where the layout has it from A.
  task::SceneLayout drawn = layout;
  drawn.cube_size = scene.script.cube_size;
  const Eigen::Vector3d a(scene.script.cube_centre.x(), 0.0, scene.script.cube_centre.z());
  drawn.zone_b = a + (layout.zone_b - layout.zone_a);
  drawn.zone_a = a;
  render::SimDrawStyle style;
  style.contacts = contacts;
  return render::draw_sim_state(drawn, scene.flesh, scene.model, *shared_->state, style);
}

PinchSimulation::Progress PinchSimulation::progress() const {
  std::lock_guard lock(shared_->mutex);
  return shared_->progress;
}

QString PinchSimulation::error() const {
  std::lock_guard lock(shared_->mutex);
  return shared_->error;
}

}  // namespace handlab::gui
