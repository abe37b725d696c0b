// What the participants page shows of a study, as rows of text: the enrolled participants
// (id, age, sex, handedness, hand length in cm, VR experience, group, notes, trials done of
// planned, status) and one participant's schedule (trial, block, order, condition, repetition,
// questionnaire, status, result; practice shaded).
#pragma once

#include <vector>

#include <QCoreApplication>
#include <QStringList>

#include "app/gui/text_table_model.h"
#include "core/store/study_store.h"

namespace handlab::gui {

class StudyTables {
  Q_DECLARE_TR_FUNCTIONS(StudyTables)

 public:
  static QStringList participant_headers();
  static QStringList schedule_headers();
  static constexpr int kGroupColumn = 6;           // of the participants
  static constexpr int kScheduleStatusColumn = 6;  // of the schedule
  // `in_session`: the participant whose session this app runs ("in session", not interrupted).
  static std::vector<TextRow> participants(store::StudyStore& store, const QString& in_session);
  static std::vector<TextRow> schedule(store::StudyStore& store, const QString& participant);
};

}  // namespace handlab::gui
