// Simulated participants (docs/simulated-participants.md) as a session's tracker: each trial's
// person sees the display and acts on it, and carries its memory to its next trial.
#include <memory>

#include "studies/participant/own_hand.h"
#include "studies/participant/simulated_participant.h"
#include "studies/session/scripted_tracker.h"
#include "studies/session/tracker.h"
#include "studies/session/trial_display.h"

namespace handlab::studies {
namespace {

class SimulatedSource : public TrialFrameSource {
 public:
  // `own` outlives the participant, which holds it by reference.
  SimulatedSource(std::shared_ptr<const OwnHand> own, const SimulatedPerson& person,
                  const SeenTrial& trial, ParticipantMemory memory)
      : own_(std::move(own)),
        participant_(
            std::make_unique<SimulatedParticipant>(person, *own_, trial, std::move(memory))) {}
  std::optional<tracking::TrackedFrame> next(const Observation& shown) override {
    return participant_->act(shown);
  }
  void finish(TrialRun& run) const override {
    run.experience = participant_->experience();
    run.participant_memory = memory_to_json(participant_->memory_after());
  }

 private:
  std::shared_ptr<const OwnHand> own_;
  std::unique_ptr<SimulatedParticipant> participant_;
};

class Simulated : public Tracker {
 public:
  Simulated(std::uint64_t seed, const ParticipantModel& model) : seed_(seed), model_(model) {}

  std::string name() const override { return "simulated (seed " + std::to_string(seed_) + ")"; }

  retarget::Calibration calibrate(const Protocol& protocol, const store::Participant& participant,
                                  const hand::Skeleton& first_hand,
                                  SessionControl* control) const override {
    return scripted_calibration(protocol.scene, participant.hand_length, first_hand, control);
  }

  // The trial's person: from who it is, what it sees of the trial and what it remembers;
  // nothing of the condition is in scope here.
  std::unique_ptr<TrialFrameSource> open(const TrialSetup& setup, const hand::Skeleton&,
                                         double rate_hz, TrialCache& cache) const override {
    const std::string& memory = setup.participant_memory;
    return std::make_unique<SimulatedSource>(
        cache.own_hand(setup.participant.hand_length),
        simulated_person(setup.participant, seed_, model_), seen_trial_of(setup, rate_hz),
        memory.empty() ? ParticipantMemory{} : memory_from_json(memory));
  }

  std::optional<QuestionnaireResponder> own_answers() const override {
    return simulated_responder(seed_);
  }

 private:
  std::uint64_t seed_;
  ParticipantModel model_;
};

}  // namespace

TrackerPtr simulated_tracker(std::uint64_t seed, const ParticipantModel& model) {
  return std::make_shared<const Simulated>(seed, model);
}

}  // namespace handlab::studies
