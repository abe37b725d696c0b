// The questionnaire in a dialog over the experimenter's window (no participant window open):
// the form of questionnaire_form.h; it closes only when every item has an answer.
#pragma once

#include <QDialog>

#include "studies/protocol/protocol.h"

namespace handlab::gui {

class QuestionnaireForm;

class QuestionnaireDialog : public QDialog {
  Q_OBJECT

 public:
  QuestionnaireDialog(const studies::Protocol& protocol, int trial_number,
                      QWidget* parent = nullptr);
  // A form already begun elsewhere (the participant's window closed while it was asked).
  QuestionnaireDialog(QuestionnaireForm* form, QWidget* parent = nullptr);
  QuestionnaireForm* form() const { return form_; }

 protected:
  void keyPressEvent(QKeyEvent* event) override;
  void reject() override;  // Escape does not skip the questions

 private:
  QuestionnaireForm* form_ = nullptr;
};

}  // namespace handlab::gui
