// The participant's window: the scene and a short instruction, full screen on a chosen
// screen. It shows nothing of the condition, the strategy or the experimenter's panel.
#pragma once

#include <memory>

#include <QWidget>

#include "core/render/draw_list.h"
#include "core/task/scene_layout.h"

class QLabel;

namespace handlab::gui {

class SceneView;

class ParticipantWindow : public QWidget {
  Q_OBJECT

 public:
  explicit ParticipantWindow(QWidget* parent = nullptr);
  void set_frame(const task::SceneLayout& layout, std::shared_ptr<const render::DrawList> frame);
  void set_instruction(const QString& text);
  QString instruction() const;
  SceneView* view() const { return view_; }
  // Full screen on screen `index` of QGuiApplication::screens() (windowed when absent).
  void show_on_screen(int index);

 private:
  SceneView* view_ = nullptr;
  QLabel* instruction_ = nullptr;
};

}  // namespace handlab::gui
