#include "app/gui/questionnaire_dialog.h"

#include <QButtonGroup>
#include <QDialogButtonBox>
#include <QGridLayout>
#include <QKeyEvent>
#include <QLabel>
#include <QPushButton>
#include <QRadioButton>
#include <QVBoxLayout>

namespace handlab::gui {

QuestionnaireDialog::QuestionnaireDialog(const studies::Protocol& protocol, int trial_number,
                                         QWidget* parent)
    : QDialog(parent), scale_(protocol.scale_points) {
  setWindowTitle(tr("Questionnaire after trial %1").arg(trial_number));
  setObjectName("questionnaire");
  auto* layout = new QVBoxLayout(this);
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
      button->setFocusPolicy(Qt::NoFocus);  // the keys 1..n go to the dialog
      group->addButton(button, v);
      grid->addWidget(button, 0, v - 1, Qt::AlignHCenter);
      auto* label = new QLabel(anchor);
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
  }
  buttons_ = new QDialogButtonBox(QDialogButtonBox::Ok);
  buttons_->button(QDialogButtonBox::Ok)->setText(tr("Save Answers"));
  connect(buttons_, &QDialogButtonBox::accepted, this, [this] {
    if (complete()) accept();
  });
  layout->addWidget(buttons_);
  // Tall enough for the anchors as they wrap at this width ("Neither easy nor difficult").
  constexpr int kWidth = 640;
  resize(kWidth,
         layout->hasHeightForWidth() ? layout->totalHeightForWidth(kWidth) : sizeHint().height());
  update_state();
}

std::vector<int> QuestionnaireDialog::answers() const {
  std::vector<int> values;
  for (const QButtonGroup* g : groups_) values.push_back(std::max(0, g->checkedId()));
  return values;
}

bool QuestionnaireDialog::complete() const {
  for (int v : answers())
    if (v < 1) return false;
  return true;
}

void QuestionnaireDialog::answer_current(int value) {
  if (groups_.empty() || value < 1 || value > scale_) return;
  groups_[std::size_t(current_)]->button(value)->setChecked(true);
  current_ = std::min(int(groups_.size()) - 1, current_ + 1);
  update_state();
}

void QuestionnaireDialog::keyPressEvent(QKeyEvent* event) {
  const int key = event->key();
  if (key >= Qt::Key_1 && key < Qt::Key_1 + scale_) {
    answer_current(key - Qt::Key_0);
    return;
  }
  if (key == Qt::Key_Up || key == Qt::Key_Down) {
    current_ = std::clamp(current_ + (key == Qt::Key_Down ? 1 : -1), 0, int(groups_.size()) - 1);
    update_state();
    return;
  }
  if ((key == Qt::Key_Return || key == Qt::Key_Enter) && complete()) {
    accept();
    return;
  }
  if (key == Qt::Key_Escape) return;
  QDialog::keyPressEvent(event);
}

void QuestionnaireDialog::reject() {
  // Every item must be answered: closing the window does not skip them.
}

void QuestionnaireDialog::update_state() {
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
}

}  // namespace handlab::gui
