// The questionnaire after a trial: the protocol's items with their texts and every anchor,
// answered with the mouse or with the keys 1..n (the item with focus, then the next). It
// closes only when every item has an answer.
#pragma once

#include <vector>

#include <QDialog>

#include "studies/protocol/protocol.h"

class QButtonGroup;
class QDialogButtonBox;
class QLabel;

namespace handlab::gui {

class QuestionnaireDialog : public QDialog {
  Q_OBJECT

 public:
  QuestionnaireDialog(const studies::Protocol& protocol, int trial_number,
                      QWidget* parent = nullptr);
  // One value per item, 1..scale; 0 where not answered yet.
  std::vector<int> answers() const;
  bool complete() const;
  int current_item() const { return current_; }
  // Answers the current item (as the key `value` does) and moves to the next.
  void answer_current(int value);

 protected:
  void keyPressEvent(QKeyEvent* event) override;
  void reject() override;  // Escape does not skip the questions

 private:
  void update_state();

  int scale_ = 5;
  int current_ = 0;
  std::vector<QButtonGroup*> groups_;
  std::vector<QLabel*> titles_;
  QDialogButtonBox* buttons_ = nullptr;
  QLabel* hint_ = nullptr;
};

}  // namespace handlab::gui
