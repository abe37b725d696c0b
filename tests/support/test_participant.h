// An enrollable participant for tests that need one but not any particular one.
#pragma once

#include <string>

#include "core/store/study_store.h"

namespace handlab::test {

inline store::Participant participant(const std::string& id, double hand_length = 0.18) {
  store::Participant p;
  p.id = id;
  p.age = 31;
  p.sex = "F";
  p.handedness = "right";
  p.hand_length = hand_length;
  p.vr_experience = "some";
  return p;
}

}  // namespace handlab::test
