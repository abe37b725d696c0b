// A trial's phase in words: what the participant reads (what to do now, never the condition)
// and what the experimenter's panel says.
#pragma once

#include <QObject>
#include <QString>

#include "core/task/cube_task.h"

namespace handlab::gui {

inline QString instruction(task::TaskPhase phase) {
  switch (phase) {
    case task::TaskPhase::kReady:
    case task::TaskPhase::kStarted:
      return QObject::tr("Pick up the cube with thumb and index finger.");
    case task::TaskPhase::kGrasped:
      return QObject::tr("Carry the cube to the blue square and put it down.");
    case task::TaskPhase::kReleased:
      return QObject::tr("Let the cube rest in the blue square.");
    case task::TaskPhase::kDone:
      return QObject::tr("Done. Take your hand back.");
    case task::TaskPhase::kFailed:
      return QObject::tr("Time is up. Take your hand back.");
  }
  return {};
}

inline QString phase_text(task::TaskPhase phase) {
  switch (phase) {
    case task::TaskPhase::kReady:
    case task::TaskPhase::kStarted:
      return QObject::tr("waiting for the grasp over A");
    case task::TaskPhase::kGrasped:
      return QObject::tr("grasped");
    case task::TaskPhase::kReleased:
      return QObject::tr("released");
    case task::TaskPhase::kDone:
      return QObject::tr("done");
    case task::TaskPhase::kFailed:
      return QObject::tr("timed out");
  }
  return {};
}

}  // namespace handlab::gui
