// Runs a participant's session from the study database: walks the stored schedule from the
// first unfinished trial, runs each through a trial driver with its frames logged off the
// simulation thread, asks the questionnaire when the protocol says so, and commits each
// trial's outcome, events and answers in one transaction. After a crash, a resumed session
// marks the interrupted trial aborted (kept) and runs it again.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/sim/step_totals.h"
#include "core/store/study_store.h"
#include "studies/participant/activity_time.h"
#include "studies/protocol/protocol.h"
#include "studies/protocol/protocol_store.h"
#include "studies/session/questionnaire_responder.h"
#include "studies/session/session_control.h"
#include "studies/session/trial_driver.h"

namespace handlab::studies {

struct SessionReport {
  int trials_run = 0, aborted_before = 0;
  bool schedule_complete = false;
  bool stopped = false;  // by a stop request (SessionControl)
  // The soft hand's steps of every trial run, per condition label (TrialRun::simulator).
  std::map<std::string, sim::StepTotals> simulator;
  // Where a simulated participant's time went in the trials run to their result (not those
  // stopped by the experimenter), by the cube they saw (its side in m, to the millimetre).
  std::map<double, ActivityTime> participant_time;
};

class SessionRunner {
 public:
  SessionRunner(store::StudyStore& store, TrialDriver& driver, QuestionnaireResponder responder);

  // resume: continue a participant who has results or an interrupted session. Without it
  // the runner refuses to touch a started schedule. `progress` gets a line per trial.
  SessionReport run(const std::string& participant_id, const std::string& tracker_name, bool resume,
                    const std::function<void(const std::string&)>& progress = {});

  // Without frames, the trials' frame records are not stored (a simulated study's choice:
  // about 160 kB a simulated second); trials then record 0 frames.
  void log_frames(bool on) { log_frames_ = on; }
  // A front end's requests and observers (session_control.h); null: none.
  void attach(SessionControl* control) { control_ = control; }

 private:
  struct Session;  // what the session's trials share
  bool run_planned_trial(Session& session, const store::PlannedTrialRow& next,
                         SessionReport& report,
                         const std::function<void(const std::string&)>& progress);
  void apply_decisions(const std::string& participant_id, std::int64_t session);

  bool log_frames_ = true;
  SessionControl* control_ = nullptr;
  store::StudyStore& store_;
  TrialDriver& driver_;
  QuestionnaireResponder responder_;
};

// The experimenter's skip between sessions: recorded in a session of its own
// ("experimenter", ended "stopped"), as a skip during a session is recorded in that one.
void skip_trial_between_sessions(store::StudyStore& store, const std::string& participant_id,
                                 int position, const std::string& reason);

}  // namespace handlab::studies
