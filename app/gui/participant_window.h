// The participant's window: the scene and a short instruction, full screen on a chosen
// screen, and the questionnaire in the scene's place while it is asked. It shows nothing of
// the condition, the strategy or the experimenter's panel.
#pragma once

#include <memory>

#include <QWidget>

#include "core/render/draw_list.h"
#include "core/task/scene_layout.h"

class QLabel;
class QStackedWidget;

namespace handlab::gui {

class QuestionnaireForm;
class SceneView;

class ParticipantWindow : public QWidget {
  Q_OBJECT

 public:
  explicit ParticipantWindow(QWidget* parent = nullptr);
  void set_frame(const task::SceneLayout& layout, std::shared_ptr<const render::DrawList> frame);
  void set_instruction(const QString& text);
  QString instruction() const;
  SceneView* view() const { return view_; }
  // The questions in place of the scene, with the keyboard's focus, until end_questionnaire()
  // (which deletes the form).
  void show_questionnaire(QuestionnaireForm* form);
  void end_questionnaire();
  QuestionnaireForm* questionnaire() const { return questionnaire_; }
  // Full screen on screen `index` of QGuiApplication::screens() (windowed when absent).
  void show_on_screen(int index);

 signals:
  // Closed while the questions were asked: the form, no longer the window's, for the
  // experimenter's window to ask them in.
  void questionnaire_left(QuestionnaireForm* form);

 protected:
  void closeEvent(QCloseEvent* event) override;

 private:
  QStackedWidget* pages_ = nullptr;  // the scene, or the questionnaire
  QWidget* scene_page_ = nullptr;
  SceneView* view_ = nullptr;
  QLabel* instruction_ = nullptr;
  QuestionnaireForm* questionnaire_ = nullptr;
};

}  // namespace handlab::gui
