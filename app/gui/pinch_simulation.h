// The scripted pinch-and-lift, simulated live in the app: the soft hand comes down over the
// cube, pinches it between thumb and index, lifts, holds and releases it. The simulator
// steps on a worker thread (building the flesh mesh takes about a second, a step some
// milliseconds); the view draws the newest state: the flesh deforming, the cube and, on
// request, the contact points.
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>

#include <QObject>

#include "core/render/draw_list.h"
#include "core/task/scene_layout.h"

namespace handlab::gui {

class PinchSimulation : public QObject {
  Q_OBJECT

 public:
  // Runs the script for the cube side (m) up to `until` seconds of simulated time (the
  // script's end when 0).
  PinchSimulation(double cube_size, double until, QObject* parent = nullptr);
  ~PinchSimulation() override;  // stops the worker and waits for it

  void stop();
  bool finished() const { return finished_; }
  bool has_state() const;
  // The newest state, drawn in `layout` (the cube's size and pose are the simulation's).
  render::DrawList draw(const task::SceneLayout& layout, bool contacts) const;

  struct Progress {
    double time = 0.0;     // s of simulated time
    double step_ms = 0.0;  // wall time of the last step
    int contacts = 0;
  };
  Progress progress() const;
  QString error() const;  // why the simulation stopped early, if it did

 signals:
  void advanced();  // a new state is there (at most one pending at a time)
  void done();

 private:
  struct Shared;
  void run(double cube_size, double until);

  std::unique_ptr<Shared> shared_;
  std::atomic<bool> stop_{false}, finished_{false}, pending_{false};
  std::thread worker_;
};

}  // namespace handlab::gui
