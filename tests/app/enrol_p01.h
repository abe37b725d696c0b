// P01, a right-handed man new to VR, enrolled into a study file: the app tests' participant.
#pragma once

#include <QString>

#include "core/store/study_store.h"
#include "studies/session/enrolment.h"

namespace handlab::gui::testing {

inline void enrol_p01(const QString& db, int age = 30, double hand_length = 0.18) {
  store::StudyStore store(db.toStdString());
  store::Participant p;
  p.id = "P01";
  p.age = age;
  p.sex = "M";
  p.handedness = "right";
  p.hand_length = hand_length;
  p.vr_experience = "none";
  studies::enrol_participant(store, p);
}

}  // namespace handlab::gui::testing
