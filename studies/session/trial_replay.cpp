#include "studies/session/trial_replay.h"

#include <algorithm>
#include <stdexcept>

#include "studies/protocol/protocol.h"
#include "studies/protocol/protocol_store.h"

namespace handlab::studies {

const store::FrameRecord& TrialReplay::frame_at(double time) const {
  if (frames.empty()) throw std::logic_error("a replay without frames");
  const auto after =
      std::upper_bound(frames.begin(), frames.end(), time,
                       [](double t, const store::FrameRecord& f) { return t < double(f.time); });
  return after == frames.begin() ? frames.front() : *(after - 1);
}

TrialReplay load_trial_replay(store::StudyStore& store, const std::string& participant,
                              int position, int attempt) {
  if (!store.participant(participant))
    throw std::runtime_error("no participant '" + participant + "' in this study");
  const auto plan = store.plan(participant);
  const auto planned =
      std::find_if(plan.begin(), plan.end(), [&](const auto& p) { return p.position == position; });
  if (planned == plan.end())
    throw std::runtime_error(participant + " has no trial " + std::to_string(position + 1) +
                             " (the schedule has " + std::to_string(plan.size()) + ")");
  // The attempt asked for, or the latest one with frames (counted in the log itself: an
  // attempt cut short by a crash has frames and no count in its row).
  const auto trials = store.trials(participant);
  const store::TrialRow* chosen = nullptr;
  for (const store::TrialRow& t : trials) {
    if (t.position != position) continue;
    if (attempt > 0 ? t.attempt == attempt : store.frame_count(t.id) > 0) chosen = &t;
  }
  const std::string which = "trial " + std::to_string(position + 1) + " of " + participant;
  if (!chosen)
    throw std::runtime_error(attempt > 0
                                 ? which + " has no attempt " + std::to_string(attempt)
                                 : which +
                                       " has no logged frames (not run yet, skipped, or run by a "
                                       "simulated study without --frames)");

  const Protocol protocol = stored_protocol(store);
  const std::vector<Condition> conditions = protocol.conditions();
  const Condition& condition = conditions.at(std::size_t(planned->condition));
  TrialReplay replay;
  replay.participant = participant;
  replay.position = position;
  replay.attempt = chosen->attempt;
  replay.status = chosen->status;
  replay.condition = condition.label;
  replay.layout = protocol.scene;
  replay.layout.cube_size = condition.cube_size;
  replay.simulated_hand = condition.simulated_hand;
  replay.frames = store.frames(chosen->id);
  if (replay.frames.empty())
    throw std::runtime_error(which + ", attempt " + std::to_string(chosen->attempt) +
                             ", has no logged frames");
  return replay;
}

}  // namespace handlab::studies
