#include "app/gui/questionnaire_dialog.h"

#include <QKeyEvent>
#include <QVBoxLayout>

#include "app/gui/questionnaire_form.h"

namespace handlab::gui {

QuestionnaireDialog::QuestionnaireDialog(const studies::Protocol& protocol, int trial_number,
                                         QWidget* parent)
    : QuestionnaireDialog(new QuestionnaireForm(protocol, false), parent) {
  setWindowTitle(tr("Questionnaire after trial %1").arg(trial_number));
}

QuestionnaireDialog::QuestionnaireDialog(QuestionnaireForm* form, QWidget* parent)
    : QDialog(parent), form_(form) {
  setWindowTitle(tr("Questionnaire"));
  setObjectName("questionnaire");
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(form_);
  connect(form_, &QuestionnaireForm::saved, this, &QDialog::accept);
  // Tall enough for the anchors as they wrap at this width ("Neither easy nor difficult").
  constexpr int kWidth = 640;
  resize(kWidth,
         layout->hasHeightForWidth() ? layout->totalHeightForWidth(kWidth) : sizeHint().height());
  form_->setFocus();
}

void QuestionnaireDialog::keyPressEvent(QKeyEvent* event) {
  if (event->key() == Qt::Key_Escape || form_->take_key(event->key())) return;
  QDialog::keyPressEvent(event);
}

void QuestionnaireDialog::reject() {
  // Every item must be answered: closing the window does not skip them.
}

}  // namespace handlab::gui
