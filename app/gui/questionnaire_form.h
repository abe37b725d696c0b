// The questionnaire after a trial: the protocol's items with their texts and every anchor,
// answered with the mouse or with the keys 1..n (the underlined item takes the key, then the
// next; Up and Down move between items; Enter saves once every item has an answer). Shown in
// a dialog over the experimenter's window, or full size in the participant's window.
#pragma once

#include <vector>

#include <QWidget>

#include "studies/protocol/protocol.h"

class QButtonGroup;
class QDialogButtonBox;
class QLabel;

namespace handlab::gui {

class QuestionnaireForm : public QWidget {
  Q_OBJECT

 public:
  // `large`: the participant's window, read from a seat away from the screen.
  QuestionnaireForm(const studies::Protocol& protocol, bool large, QWidget* parent = nullptr);
  // One value per item, 1..scale; 0 where not answered yet.
  std::vector<int> answers() const;
  bool complete() const;
  int current_item() const { return current_; }
  // Answers the current item (as the key `value` does) and moves to the next.
  void answer_current(int value);
  // A key press as the form takes it; false when it is not the form's.
  bool take_key(int key);

 signals:
  void saved();    // every item answered, then Save or Enter
  void changed();  // an answer given or the current item moved: what it shows is new

 protected:
  void keyPressEvent(QKeyEvent* event) override;

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
