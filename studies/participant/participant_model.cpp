#include "studies/participant/participant_model.h"

#include <cmath>
#include <cstdio>

#include "core/util/portable_random.h"
#include "studies/participant/motor_primitives.h"

namespace handlab::studies {

std::uint64_t person_seed(std::uint64_t seed, const std::string& id) {
  return util::fnv1a64(id) ^ (0x9E3779B97F4A7C15ull * (seed + 1));
}

MotorParameters draw_motor_parameters(std::uint64_t seed, const std::string& id) {
  // A stream of its own, apart from the covariates' (so adding a parameter here never moves
  // a person's age or hand length).
  MotorRandom r(person_seed(seed, id) ^ 0xD1B54A32D192ED03ull);
  MotorParameters m;
  m.reaction_mu = r.truncated_normal(0.25, 0.03, 0.15, 0.40);
  m.visual_delay = r.truncated_normal(0.12, 0.02, 0.08, 0.18);
  m.fitts_a = r.truncated_normal(0.50, 0.10, 0.30, 0.90);
  m.fitts_b = r.truncated_normal(0.40, 0.05, 0.25, 0.60);
  m.aperture_intercept = r.truncated_normal(0.075, 0.008, 0.055, 0.095);
  m.closing_time = r.truncated_normal(0.50, 0.08, 0.30, 0.80);
  m.tremor_hz = 8.0 + 4.0 * r.uniform();
  m.practice_exponent = r.truncated_normal(0.20, 0.05, 0.05, 0.40);
  return m;
}

SimulatedPerson draw_person(const Population& p, std::uint64_t seed, int index) {
  char id[16];
  std::snprintf(id, sizeof id, "S%02d", index + 1);
  SimulatedPerson person;
  person.seed = person_seed(seed, id);
  MotorRandom r(person.seed);
  store::Participant& q = person.participant;
  q.id = id;
  q.age = int(std::lround(r.truncated_normal(p.age_mean, p.age_sd, p.age_min, p.age_max)));
  q.sex = r.uniform() < p.male_fraction ? "M" : "F";
  q.handedness = "right";
  // Stored to the tenth of a millimetre, as a person's measurement is.
  q.hand_length = std::round(1e4 * r.truncated_normal(p.hand_length_mean, p.hand_length_sd,
                                                      p.hand_length_min, p.hand_length_max)) /
                  1e4;
  q.vr_experience = r.uniform() < p.vr_experience_fraction ? "yes" : "none";
  q.notes =
      "simulated participant (handlab participant model 1, seed " + std::to_string(seed) + ")";
  q.simulated = true;
  person.motor = draw_motor_parameters(seed, id);
  return person;
}

}  // namespace handlab::studies
