#include "studies/participant/questionnaire_model.h"

#include <algorithm>
#include <cmath>

#include "studies/participant/motor_primitives.h"

namespace handlab::studies {
namespace {

constexpr QuestionnaireModel kModel{};

const QuestionnaireWeights& weights_of(const std::string& id) {
  if (id == "precision") return kModel.precision;
  if (id == "ease") return kModel.ease;
  if (id == "naturalness") return kModel.naturalness;
  return kModel.other;
}

}  // namespace

std::vector<int> simulated_answers(const std::vector<std::string>& item_ids, int scale_points,
                                   const TrialExperience& e, double time, std::uint64_t seed) {
  MotorRandom random(seed);
  const double extra_attempts = std::max(e.grasp_attempts - 1, 0);
  const double doublings =
      e.expected_time > 0 ? std::max(std::log2(std::max(time, 1e-3) / e.expected_time), 0.0) : 0.0;
  std::vector<int> answers;
  for (const std::string& id : item_ids) {
    const QuestionnaireWeights& w = weights_of(id);
    const double latent = double(scale_points) - w.attempt * extra_attempts -
                          w.correction * e.corrections - w.loss * e.losses -
                          w.doubling * doublings + random.normal(0.0, kModel.noise_sd);
    answers.push_back(std::clamp(int(std::lround(latent)), 1, scale_points));
  }
  return answers;
}

}  // namespace handlab::studies
