#include "studies/session/questionnaire_responder.h"

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

}  // namespace handlab::studies
