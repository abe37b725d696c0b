// Add or edit a participant: the store's rules checked as the values are typed
// (studies/session/enrolment.h), each refused value marked with the reason; OK only when
// everything is acceptable. The hand length is entered in centimetres.
#pragma once

#include <optional>
#include <vector>

#include <QDialog>

#include "core/store/study_store.h"
#include "studies/protocol/protocol.h"

class QComboBox;
class QDialogButtonBox;
class QDoubleSpinBox;
class QLabel;
class QLineEdit;
class QSpinBox;

namespace handlab::gui {

class ParticipantForm : public QDialog {
  Q_OBJECT

 public:
  // `editing`: the participant to change (its id fixed); null: a new one. With the study's
  // protocol, a field that places the participant in no group of a between factor it decides
  // is refused too, and the VR experience offers the protocol's answers.
  ParticipantForm(std::vector<store::Participant> enrolled, const store::Participant* editing,
                  QWidget* parent = nullptr, const studies::Protocol* protocol = nullptr);
  store::Participant participant() const;
  // The reasons shown now (empty: acceptable).
  QStringList problems() const;

  QLineEdit* id_edit() const { return id_; }
  QSpinBox* age_box() const { return age_; }
  QComboBox* sex_box() const { return sex_; }
  QComboBox* handedness_box() const { return handedness_; }
  QDoubleSpinBox* hand_length_box() const { return hand_length_; }
  QComboBox* vr_box() const { return vr_; }
  QLineEdit* notes_edit() const { return notes_; }
  QDialogButtonBox* buttons() const { return buttons_; }

 private:
  void validate();

  std::vector<store::Participant> enrolled_;
  std::optional<studies::Protocol> protocol_;
  bool editing_ = false;
  QLineEdit *id_ = nullptr, *notes_ = nullptr;
  QSpinBox* age_ = nullptr;
  QComboBox *sex_ = nullptr, *handedness_ = nullptr, *vr_ = nullptr;
  QDoubleSpinBox* hand_length_ = nullptr;
  QLabel* problems_ = nullptr;
  QDialogButtonBox* buttons_ = nullptr;
  QStringList current_problems_;
};

}  // namespace handlab::gui
