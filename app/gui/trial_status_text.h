// A trial's status as the experimenter reads it in the schedule and in a replay.
#pragma once

#include <QObject>
#include <QString>

#include "core/store/study_store.h"

namespace handlab::gui {

inline QString trial_status_text(store::TrialStatus status) {
  switch (status) {
    case store::TrialStatus::kRunning:
      return QObject::tr("running");
    case store::TrialStatus::kCompleted:
      return QObject::tr("done");
    case store::TrialStatus::kTimeout:
      return QObject::tr("timed out");
    case store::TrialStatus::kAborted:
      return QObject::tr("aborted");
    case store::TrialStatus::kSkipped:
      return QObject::tr("skipped");
    case store::TrialStatus::kRedone:
      return QObject::tr("redone");
  }
  return {};
}

}  // namespace handlab::gui
