#include "studies/session/session_runner.h"

#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/store/frame_logger.h"

namespace handlab::studies {

void skip_trial_between_sessions(store::StudyStore& store, const std::string& participant_id,
                                 int position, const std::string& reason) {
  const std::int64_t session = store.begin_session(participant_id, "experimenter");
  try {
    store.skip_trial(participant_id, position, session, reason);
  } catch (...) {
    store.end_session(session, "stopped");  // no session left open by a refused skip
    throw;
  }
  store.end_session(session, "stopped");
}

SessionRunner::SessionRunner(store::StudyStore& store, TrialDriver& driver,
                             QuestionnaireResponder responder)
    : store_(store), driver_(driver), responder_(std::move(responder)) {}

namespace {

// The trial at `planned` of the session's schedule, as the driver runs it.
TrialSetup setup_of(const Protocol& protocol, const std::vector<Condition>& conditions,
                    const store::Participant& participant, const store::PlannedTrialRow& planned,
                    const retarget::Calibration& calibration, std::string memory) {
  TrialSetup setup;
  setup.protocol = &protocol;
  setup.condition = conditions.at(std::size_t(planned.condition));
  setup.participant = participant;
  setup.planned = planned;
  setup.calibration = calibration;
  // Calibrated for the first condition's hand; the box ratio scales with the hand's length.
  setup.calibration.scale *=
      setup.condition.simulated_hand_length / conditions.front().simulated_hand_length;
  setup.participant_memory = std::move(memory);
  return setup;
}

// The responder's answers to the protocol's items, checked against its scale.
std::vector<std::pair<std::string, int>> answers_of(const QuestionnaireResponder& responder,
                                                    const Protocol& protocol,
                                                    const std::string& participant_id, int position,
                                                    const TrialRun& run) {
  SeenQuestionnaire asked{participant_id, position, protocol.timeout_s, {}, protocol.scale_points};
  for (const QuestionnaireItem& item : protocol.items) asked.item_ids.push_back(item.id);
  const std::vector<int> values = responder(asked, run);
  if (values.size() != protocol.items.size())
    throw std::runtime_error("the questionnaire needs one answer per item");
  std::vector<std::pair<std::string, int>> answers;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] < 1 || values[i] > protocol.scale_points)
      throw std::runtime_error("answer out of the scale for " + protocol.items[i].id);
    answers.emplace_back(protocol.items[i].id, values[i]);
  }
  return answers;
}

store::TrialOutcome outcome_of(const TrialRun& run, std::int64_t frames_stored) {
  store::TrialOutcome outcome;
  outcome.success = run.success;
  outcome.completion_time_s = run.completion_time_s;
  outcome.grasps = run.grasps;
  outcome.drops = run.drops;
  outcome.frames = int(frames_stored);
  outcome.events = run.events;
  outcome.participant_memory = run.participant_memory;
  return outcome;
}

std::string progress_line(const std::string& participant_id, const store::PlannedTrialRow& next,
                          int planned, const std::string& label, const TrialRun& run) {
  std::ostringstream line;
  line << participant_id << " trial " << next.position + 1 << "/" << planned << " "
       << (next.practice ? "practice " : "block " + std::to_string(next.block) + " ") << label
       << ": " << (run.success ? "done in " : "timed out at ") << run.completion_time_s << " s, "
       << run.grasps << " grasps, " << run.drops << " drops, " << run.frames << " frames";
  return line.str();
}

// The trial's costs in the session's totals (the simulator's only where it ran).
void tally(const TrialSetup& setup, const TrialRun& run, SessionReport& report) {
  if (run.simulator.steps > 0) report.simulator[setup.condition.label] += run.simulator;
  if (run.experience && !run.aborted)
    report.participant_time[std::round(run.experience->cube_size * 1e3) / 1e3] +=
        run.experience->time;
}

}  // namespace

struct SessionRunner::Session {
  std::string participant_id;
  store::Participant participant;
  Protocol protocol;
  std::vector<Condition> conditions;
  retarget::Calibration calibration;
  std::int64_t id = 0;
  int planned = 0;
  std::optional<store::FrameLogger> logger;
};

SessionReport SessionRunner::run(const std::string& participant_id, const std::string& tracker_name,
                                 bool resume,
                                 const std::function<void(const std::string&)>& progress) {
  const auto participant = store_.participant(participant_id);
  if (!participant)
    throw std::runtime_error("no participant " + participant_id + " in " + store_.path());
  Session s{participant_id, *participant, stored_protocol(store_), {}, {}, 0, 0, std::nullopt};
  s.conditions = s.protocol.conditions();
  SessionReport report;
  if (store_.has_started(participant_id) && !resume)
    throw std::runtime_error(participant_id +
                             " has already started the schedule; continue it with --resume");
  report.aborted_before = store_.abort_interrupted(participant_id);
  if (!store_.next_trial(participant_id)) {
    report.schedule_complete = true;
    return report;
  }
  driver_.attach(control_);
  try {
    s.calibration = driver_.calibrate(s.protocol, s.participant);
  } catch (const SessionStopped&) {
    report.stopped = true;
    return report;
  }
  s.id = store_.begin_session(participant_id, tracker_name);
  if (log_frames_) s.logger.emplace(store_.path());
  s.planned = int(store_.plan(participant_id).size());
  while (true) {
    if (control_) {
      apply_decisions(participant_id, s.id);
      if (!control_->hold_while_paused()) {
        report.stopped = true;
        break;
      }
      apply_decisions(participant_id, s.id);  // those made while paused
    }
    const std::optional<store::PlannedTrialRow> next = store_.next_trial(participant_id);
    if (!next || !run_planned_trial(s, *next, report, progress)) break;
  }
  report.schedule_complete = !store_.next_trial(participant_id).has_value();
  store_.end_session(s.id, report.schedule_complete ? "finished" : "stopped");
  return report;
}

// Runs and stores one trial; false when the experimenter stopped it.
bool SessionRunner::run_planned_trial(Session& s, const store::PlannedTrialRow& next,
                                      SessionReport& report,
                                      const std::function<void(const std::string&)>& progress) {
  const TrialSetup setup = setup_of(s.protocol, s.conditions, s.participant, next, s.calibration,
                                    store_.participant_memory(s.participant_id).value_or(""));
  const std::int64_t trial = store_.begin_trial(next.id, s.id);
  if (control_ && control_->trial_started) control_->trial_started(setup, s.planned);
  std::int64_t seq = 0;
  const TrialRun run = driver_.run(setup, [&](const store::FrameRecord& frame) {
    if (s.logger) s.logger->log(trial, seq++, frame);
  });
  if (s.logger) s.logger->flush();  // every frame on disk before the outcome is committed
  tally(setup, run, report);
  if (run.aborted) {
    store_.abort_trial(trial, run.abort_reason.empty() ? "stopped by the experimenter" : run.abort_reason);
    if (control_ && control_->trial_ended) control_->trial_ended(setup, run);
    report.stopped = true;
    return false;
  }
  store::TrialOutcome outcome = outcome_of(run, seq);
  if (next.questionnaire && !s.protocol.items.empty())
    outcome.answers = answers_of(responder_, s.protocol, s.participant_id, next.position, run);
  store_.finish_trial(trial, outcome);
  ++report.trials_run;
  if (control_ && control_->trial_ended) control_->trial_ended(setup, run);
  if (progress)
    progress(progress_line(s.participant_id, next, s.planned, setup.condition.label, run));
  return true;
}

void SessionRunner::apply_decisions(const std::string& participant_id, std::int64_t session) {
  for (const TrialDecision& d : control_->take_decisions()) {
    std::string error;
    try {
      if (d.kind == TrialDecision::Kind::kRedo)
        store_.redo_trial(participant_id, d.position, d.reason);
      else
        store_.skip_trial(participant_id, d.position, session, d.reason);
    } catch (const std::exception& e) {
      error = e.what();
    }
    if (control_->decided) control_->decided(d, error);
  }
}

}  // namespace handlab::studies
