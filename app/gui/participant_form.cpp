#include "app/gui/participant_form.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>

#include "studies/session/enrolment.h"

namespace handlab::gui {

ParticipantForm::ParticipantForm(std::vector<store::Participant> enrolled,
                                 const store::Participant* editing, QWidget* parent,
                                 const studies::Protocol* protocol)
    : QDialog(parent), enrolled_(std::move(enrolled)), editing_(editing != nullptr) {
  if (protocol) protocol_ = *protocol;
  setWindowTitle(editing ? tr("Edit Participant") : tr("Add Participant"));
  setObjectName("participant_form");
  auto* form = new QFormLayout(this);
  id_ = new QLineEdit;
  id_->setObjectName("id");
  id_->setPlaceholderText(tr("e.g. P01"));
  age_ = new QSpinBox;
  age_->setObjectName("age");
  age_->setRange(0, 150);
  age_->setSpecialValueText(tr("(required)"));
  sex_ = new QComboBox;
  sex_->setObjectName("sex");
  sex_->addItem(tr("(required)"), "");
  sex_->addItem(tr("female"), "F");
  sex_->addItem(tr("male"), "M");
  sex_->addItem(tr("other or not given"), "X");
  handedness_ = new QComboBox;
  handedness_->setObjectName("handedness");
  handedness_->addItem(tr("(required)"), "");
  handedness_->addItem(tr("right"), "right");
  handedness_->addItem(tr("left"), "left");
  handedness_->addItem(tr("ambidextrous"), "ambidextrous");
  hand_length_ = new QDoubleSpinBox;
  hand_length_->setObjectName("hand_length");
  hand_length_->setRange(0.0, 40.0);
  hand_length_->setDecimals(1);
  hand_length_->setSingleStep(0.1);
  hand_length_->setSuffix(tr(" cm"));
  hand_length_->setSpecialValueText(tr("(required)"));
  hand_length_->setToolTip(tr("Wrist crease to the tip of the middle finger"));
  vr_ = new QComboBox;
  vr_->setObjectName("vr_experience");
  vr_->setEditable(true);
  vr_->addItems({"", "none", "some", "yes", "expert"});
  if (protocol_)
    for (const studies::BetweenFactor& f : protocol_->between)
      if (f.field == "vr_experience")
        for (const studies::BetweenLevel& l : f.levels)
          for (const std::string& v : l.values)
            if (vr_->findText(QString::fromStdString(v), Qt::MatchFixedString) < 0)
              vr_->addItem(QString::fromStdString(v));
  notes_ = new QLineEdit;
  notes_->setObjectName("notes");
  form->addRow(tr("Id"), id_);
  form->addRow(tr("Age (years)"), age_);
  form->addRow(tr("Sex"), sex_);
  form->addRow(tr("Handedness"), handedness_);
  form->addRow(tr("Hand length"), hand_length_);
  form->addRow(tr("VR experience"), vr_);
  form->addRow(tr("Notes"), notes_);
  problems_ = new QLabel;
  problems_->setObjectName("problems");
  problems_->setStyleSheet("QLabel { color: #b00020; }");
  problems_->setWordWrap(true);
  form->addRow(problems_);
  buttons_ = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  form->addRow(buttons_);
  connect(buttons_, &QDialogButtonBox::accepted, this, [this] {
    validate();
    if (current_problems_.isEmpty()) accept();
  });
  connect(buttons_, &QDialogButtonBox::rejected, this, &QDialog::reject);

  if (editing) {
    id_->setText(QString::fromStdString(editing->id));
    id_->setReadOnly(true);
    age_->setValue(editing->age);
    sex_->setCurrentIndex(sex_->findData(QString::fromStdString(editing->sex)));
    handedness_->setCurrentIndex(
        handedness_->findData(QString::fromStdString(editing->handedness)));
    hand_length_->setValue(editing->hand_length * 100.0);
    vr_->setCurrentText(QString::fromStdString(editing->vr_experience));
    notes_->setText(QString::fromStdString(editing->notes));
    std::erase_if(enrolled_, [&](const store::Participant& p) { return p.id == editing->id; });
  }
  connect(id_, &QLineEdit::textChanged, this, &ParticipantForm::validate);
  connect(age_, &QSpinBox::valueChanged, this, &ParticipantForm::validate);
  connect(sex_, &QComboBox::currentIndexChanged, this, &ParticipantForm::validate);
  connect(handedness_, &QComboBox::currentIndexChanged, this, &ParticipantForm::validate);
  connect(hand_length_, &QDoubleSpinBox::valueChanged, this, &ParticipantForm::validate);
  connect(vr_, &QComboBox::currentTextChanged, this, &ParticipantForm::validate);
  validate();
}

store::Participant ParticipantForm::participant() const {
  store::Participant p;
  p.id = id_->text().trimmed().toStdString();
  p.age = age_->value();
  p.sex = sex_->currentData().toString().toStdString();
  p.handedness = handedness_->currentData().toString().toStdString();
  p.hand_length = std::round(hand_length_->value() * 10.0) / 1000.0;  // cm, one decimal -> m
  p.vr_experience = vr_->currentText().trimmed().toStdString();
  p.notes = notes_->text().toStdString();
  return p;
}

QStringList ParticipantForm::problems() const {
  return current_problems_;
}

void ParticipantForm::validate() {
  current_problems_.clear();
  const auto problems =
      studies::participant_problems(participant(), enrolled_, protocol_ ? &*protocol_ : nullptr);
  QWidget* fields[] = {id_, age_, sex_, handedness_, hand_length_, vr_};
  const char* names[] = {"id", "age", "sex", "handedness", "hand_length", "vr_experience"};
  for (int f = 0; f < 6; ++f) {
    bool bad = false;
    for (const auto& p : problems) bad |= p.field == names[f];
    fields[f]->setStyleSheet(bad ? "background: #fde7e9;" : "");
  }
  for (const auto& p : problems) current_problems_ << QString::fromStdString(p.message);
  problems_->setText(current_problems_.join("\n"));
  buttons_->button(QDialogButtonBox::Ok)->setEnabled(current_problems_.isEmpty());
}

}  // namespace handlab::gui
