#include "studies/session/session_runner.h"

#include <optional>
#include <sstream>
#include <stdexcept>

#include "core/store/frame_logger.h"
#include "studies/participant/participant_model.h"
#include "studies/participant/questionnaire_model.h"

namespace handlab::studies {

QuestionnaireResponder fixed_responder() {
  return [](const SeenQuestionnaire& q, const TrialRun&) {
    return std::vector<int>(q.item_ids.size(), (q.scale_points + 1) / 2);
  };
}

QuestionnaireResponder simulated_responder(std::uint64_t seed) {
  return [seed](const SeenQuestionnaire& q, const TrialRun& run) {
    if (!run.experience) return std::vector<int>(q.item_ids.size(), (q.scale_points + 1) / 2);
    // The person's stream and the trial's place.
    const std::uint64_t stream = person_seed(seed, q.participant_id) ^
                                 (0x94D049BB133111EBull * std::uint64_t(q.position + 1));
    return simulated_answers(q.item_ids, q.scale_points, *run.experience,
                             run.success ? run.completion_time_s : q.timeout_s, stream);
  };
}

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

SessionReport SessionRunner::run(const std::string& participant_id, const std::string& tracker_name,
                                 bool resume,
                                 const std::function<void(const std::string&)>& progress) {
  const auto participant = store_.participant(participant_id);
  if (!participant)
    throw std::runtime_error("no participant " + participant_id + " in " + store_.path());
  const Protocol protocol = stored_protocol(store_);
  const std::vector<Condition> conditions = protocol.conditions();

  SessionReport report;
  if (store_.has_started(participant_id) && !resume)
    throw std::runtime_error(participant_id +
                             " has already started the schedule; continue it with --resume");
  report.aborted_before = store_.abort_interrupted(participant_id);

  std::optional<store::PlannedTrialRow> next = store_.next_trial(participant_id);
  if (!next) {
    report.schedule_complete = true;
    return report;
  }
  driver_.attach(control_);
  retarget::Calibration calibration;
  try {
    calibration = driver_.calibrate(protocol, *participant);
  } catch (const SessionStopped&) {
    report.stopped = true;
    return report;
  }
  const std::int64_t session = store_.begin_session(participant_id, tracker_name);
  std::optional<store::FrameLogger> logger;
  if (log_frames_) logger.emplace(store_.path());
  const int planned = int(store_.plan(participant_id).size());
  while (true) {
    if (control_) {
      apply_decisions(participant_id, session);
      if (!control_->hold_while_paused()) {
        report.stopped = true;
        break;
      }
      apply_decisions(participant_id, session);  // those made while paused
    }
    next = store_.next_trial(participant_id);
    if (!next) break;
    TrialSetup setup;
    setup.protocol = &protocol;
    setup.condition = conditions.at(std::size_t(next->condition));
    setup.participant = *participant;
    setup.planned = *next;
    setup.calibration = calibration;
    // Calibrated for the first condition's hand; the box ratio scales with the hand's length.
    setup.calibration.scale *=
        setup.condition.simulated_hand_length / conditions.front().simulated_hand_length;
    setup.participant_memory = store_.participant_memory(participant_id).value_or("");

    const std::int64_t trial = store_.begin_trial(next->id, session);
    if (control_ && control_->trial_started) control_->trial_started(setup, planned);
    std::int64_t seq = 0;
    const TrialRun run = driver_.run(setup, [&](const store::FrameRecord& frame) {
      if (logger) logger->log(trial, seq++, frame);
    });
    if (logger) logger->flush();  // every frame on disk before the outcome is committed
    if (run.aborted) {
      store_.abort_trial(trial, "stopped by the experimenter");
      if (control_ && control_->trial_ended) control_->trial_ended(setup, run);
      report.stopped = true;
      break;
    }

    store::TrialOutcome outcome;
    outcome.success = run.success;
    outcome.completion_time_s = run.completion_time_s;
    outcome.grasps = run.grasps;
    outcome.drops = run.drops;
    outcome.frames = int(seq);  // the frames stored
    outcome.events = run.events;
    outcome.participant_memory = run.participant_memory;
    if (next->questionnaire && !protocol.items.empty()) {
      SeenQuestionnaire asked{
          participant_id, next->position, protocol.timeout_s, {}, protocol.scale_points};
      for (const QuestionnaireItem& item : protocol.items) asked.item_ids.push_back(item.id);
      const std::vector<int> values = responder_(asked, run);
      if (values.size() != protocol.items.size())
        throw std::runtime_error("the questionnaire needs one answer per item");
      for (std::size_t i = 0; i < values.size(); ++i) {
        if (values[i] < 1 || values[i] > protocol.scale_points)
          throw std::runtime_error("answer out of the scale for " + protocol.items[i].id);
        outcome.answers.emplace_back(protocol.items[i].id, values[i]);
      }
    }
    store_.finish_trial(trial, outcome);
    ++report.trials_run;
    if (control_ && control_->trial_ended) control_->trial_ended(setup, run);
    if (progress) {
      std::ostringstream line;
      line << participant_id << " trial " << next->position + 1 << "/" << planned << " "
           << (next->practice ? "practice " : "block " + std::to_string(next->block) + " ")
           << setup.condition.label << ": " << (run.success ? "done in " : "timed out at ")
           << run.completion_time_s << " s, " << run.grasps << " grasps, " << run.drops
           << " drops, " << run.frames << " frames";
      progress(line.str());
    }
  }
  report.schedule_complete = !store_.next_trial(participant_id).has_value();
  store_.end_session(session, report.schedule_complete ? "finished" : "stopped");
  return report;
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
