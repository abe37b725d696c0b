#include "app/gui/questionnaire_form.h"

#include <QButtonGroup>
#include <QDialogButtonBox>
#include <QGridLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QPushButton>
#include <QRadioButton>
#include <QVBoxLayout>

namespace handlab::gui {

QuestionnaireForm::QuestionnaireForm(const studies::Protocol& protocol, bool large, QWidget* parent)
    : QWidget(parent), scale_(protocol.scale_points) {
  setObjectName("questionnaire_form");
  setFocusPolicy(Qt::StrongFocus);  // the keys 1..n come here
  if (large)
    setStyleSheet(
        "QLabel, QRadioButton, QPushButton { font-size: 20pt; }"
        "QLabel#anchor { font-size: 15pt; }"  // two lines under each point fit a 640 px window
        "QRadioButton::indicator { width: 28px; height: 28px; }");
  auto* layout = new QVBoxLayout(this);
  if (large) layout->setContentsMargins(48, 32, 48, 32);
  hint_ = new QLabel;
  hint_->setWordWrap(true);
  layout->addWidget(hint_);
  for (std::size_t i = 0; i < protocol.items.size(); ++i) {
    const studies::QuestionnaireItem& item = protocol.items[i];
    auto* title =
        new QLabel(QString("<b>%1.</b> %2").arg(i + 1).arg(QString::fromStdString(item.text)));
    title->setWordWrap(true);
    layout->addWidget(title);
    titles_.push_back(title);
    auto* grid = new QGridLayout;
    auto* group = new QButtonGroup(this);
    for (int v = 1; v <= scale_; ++v) {
      const std::size_t k = std::size_t(v - 1);
      const QString anchor =
          k < item.anchors.size() ? QString::fromStdString(item.anchors[k]) : QString();
      auto* button = new QRadioButton(QString::number(v));
      button->setObjectName(QString("item%1_%2").arg(i).arg(v));
      button->setFocusPolicy(Qt::NoFocus);  // the keys 1..n go to the form
      group->addButton(button, v);
      grid->addWidget(button, 0, v - 1, Qt::AlignHCenter);
      auto* label = new QLabel(anchor);
      label->setObjectName("anchor");
      label->setAlignment(Qt::AlignHCenter | Qt::AlignTop);
      label->setWordWrap(true);
      grid->addWidget(label, 1, v - 1);
    }
    connect(group, &QButtonGroup::idClicked, this, [this, i](int) {
      if (int(i) == current_) current_ = std::min(int(groups_.size()) - 1, current_ + 1);
      update_state();
    });
    for (int column = 0; column < scale_; ++column) grid->setColumnStretch(column, 1);
    groups_.push_back(group);
    layout->addLayout(grid);
    if (large) layout->addSpacing(24);
  }
  if (large) layout->addStretch(1);
  buttons_ = new QDialogButtonBox(QDialogButtonBox::Ok);
  buttons_->button(QDialogButtonBox::Ok)->setText(tr("Save Answers"));
  buttons_->button(QDialogButtonBox::Ok)->setFocusPolicy(Qt::NoFocus);
  connect(buttons_, &QDialogButtonBox::accepted, this, [this] {
    if (complete()) emit saved();
  });
  layout->addWidget(buttons_);
  update_state();
}

std::vector<int> QuestionnaireForm::answers() const {
  std::vector<int> values;
  for (const QButtonGroup* g : groups_) values.push_back(std::max(0, g->checkedId()));
  return values;
}

bool QuestionnaireForm::complete() const {
  for (int v : answers())
    if (v < 1) return false;
  return true;
}

void QuestionnaireForm::answer_current(int value) {
  if (groups_.empty() || value < 1 || value > scale_) return;
  groups_[std::size_t(current_)]->button(value)->setChecked(true);
  current_ = std::min(int(groups_.size()) - 1, current_ + 1);
  update_state();
}

bool QuestionnaireForm::take_key(int key) {
  if (key >= Qt::Key_1 && key < Qt::Key_1 + scale_) {
    answer_current(key - Qt::Key_0);
    return true;
  }
  if (key == Qt::Key_Up || key == Qt::Key_Down) {
    current_ = std::clamp(current_ + (key == Qt::Key_Down ? 1 : -1), 0, int(groups_.size()) - 1);
    update_state();
    return true;
  }
  if (key == Qt::Key_Return || key == Qt::Key_Enter) {
    if (complete()) emit saved();
    return true;
  }
  return false;
}

void QuestionnaireForm::keyPressEvent(QKeyEvent* event) {
  if (!take_key(event->key())) QWidget::keyPressEvent(event);
}

void QuestionnaireForm::update_state() {
  for (std::size_t i = 0; i < titles_.size(); ++i) {
    QFont font = titles_[i]->font();
    font.setUnderline(int(i) == current_);
    titles_[i]->setFont(font);
  }
  int missing = 0;
  for (int v : answers()) missing += v < 1;
  buttons_->button(QDialogButtonBox::Ok)->setEnabled(missing == 0);
  hint_->setText(missing ? tr("Answer each question with the mouse or the keys 1–%1 (the "
                              "underlined question takes the key). %2 left.")
                               .arg(scale_)
                               .arg(missing)
                         : tr("All answered: Save Answers (Enter)."));
  emit changed();
}

}  // namespace handlab::gui
