#include "app/gui/participant_window.h"

#include <QCloseEvent>
#include <QGuiApplication>
#include <QLabel>
#include <QScreen>
#include <QStackedWidget>
#include <QVBoxLayout>

#include "app/gui/questionnaire_form.h"
#include "app/gui/scene_view.h"

namespace handlab::gui {

ParticipantWindow::ParticipantWindow(QWidget* parent) : QWidget(parent, Qt::Window) {
  setWindowTitle(tr("handlab — participant"));
  setObjectName("participant_window");
  auto* outer = new QVBoxLayout(this);
  outer->setContentsMargins(0, 0, 0, 0);
  pages_ = new QStackedWidget;
  outer->addWidget(pages_);
  scene_page_ = new QWidget;
  pages_->addWidget(scene_page_);
  auto* layout = new QVBoxLayout(scene_page_);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(0);
  view_ = new SceneView;
  layout->addWidget(view_, 1);
  instruction_ = new QLabel(tr("Please wait."));
  instruction_->setObjectName("instruction");
  instruction_->setAlignment(Qt::AlignCenter);
  instruction_->setStyleSheet(
      "QLabel { background: #202328; color: #f0f0f0; font-size: 22pt; padding: 14px; }");
  layout->addWidget(instruction_);
  resize(960, 640);
}

void ParticipantWindow::set_frame(const task::SceneLayout& layout,
                                  std::shared_ptr<const render::DrawList> frame) {
  if (view_->layout().cube_size != layout.cube_size) view_->set_layout(layout);
  view_->set_frame(std::move(frame));
}

void ParticipantWindow::set_instruction(const QString& text) {
  if (instruction_->text() != text) instruction_->setText(text);
}

void ParticipantWindow::show_questionnaire(QuestionnaireForm* form) {
  end_questionnaire();
  questionnaire_ = form;
  pages_->addWidget(form);
  pages_->setCurrentWidget(form);
  activateWindow();
  form->setFocus();
}

void ParticipantWindow::end_questionnaire() {
  if (!questionnaire_) return;
  pages_->setCurrentWidget(scene_page_);
  pages_->removeWidget(questionnaire_);
  questionnaire_->deleteLater();
  questionnaire_ = nullptr;
}

void ParticipantWindow::closeEvent(QCloseEvent* event) {
  if (QuestionnaireForm* form = questionnaire_) {
    questionnaire_ = nullptr;
    pages_->removeWidget(form);
    form->setParent(nullptr);
    pages_->setCurrentWidget(scene_page_);
    emit questionnaire_left(form);
  }
  QWidget::closeEvent(event);
}

QString ParticipantWindow::instruction() const {
  return instruction_->text();
}

void ParticipantWindow::show_on_screen(int index) {
  const QList<QScreen*> screens = QGuiApplication::screens();
  if (index >= 0 && index < screens.size() && screens.size() > 1) {
    setScreen(screens[index]);
    setGeometry(screens[index]->geometry());
    showFullScreen();
  } else {
    showNormal();
  }
  raise();
}

}  // namespace handlab::gui
