#include "app/gui/participant_window.h"

#include <QGuiApplication>
#include <QLabel>
#include <QScreen>
#include <QVBoxLayout>

#include "app/gui/scene_view.h"

namespace handlab::gui {

ParticipantWindow::ParticipantWindow(QWidget* parent) : QWidget(parent, Qt::Window) {
  setWindowTitle(tr("handlab — participant"));
  setObjectName("participant_window");
  auto* layout = new QVBoxLayout(this);
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
