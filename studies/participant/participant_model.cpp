#include "studies/participant/participant_model.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/util/json_writer.h"
#include "core/util/portable_random.h"
#include "core/util/sha256.h"
#include "studies/participant/behaviour.h"
#include "studies/participant/motor_primitives.h"

namespace handlab::studies {

const char* const kParticipantModelVersion = "handlab participant model 2";

const std::vector<ParameterDistribution>& motor_distributions() {
  // name, mean, sd, low, high (SI units; sources in docs/simulated-participants.md)
  static const std::vector<ParameterDistribution> d = {
      {"reaction_mu", 0.25, 0.03, 0.15, 0.40},
      {"visual_delay", 0.12, 0.02, 0.08, 0.18},
      {"fitts_a", 0.55, 0.10, 0.30, 0.90},
      {"fitts_b", 0.41, 0.05, 0.25, 0.60},
      {"aperture_intercept", 0.050, 0.008, 0.030, 0.070},
      {"closing_time", 0.50, 0.08, 0.30, 0.80},
      {"tremor_hz", 10.0, 0.0, 8.0, 12.0},
      {"practice_rate", 0.35, 0.10, 0.10, 0.70},
  };
  return d;
}

namespace {

double& field(MotorParameters& m, const std::string& name) {
  if (name == "reaction_mu") return m.reaction_mu;
  if (name == "visual_delay") return m.visual_delay;
  if (name == "fitts_a") return m.fitts_a;
  if (name == "fitts_b") return m.fitts_b;
  if (name == "aperture_intercept") return m.aperture_intercept;
  if (name == "closing_time") return m.closing_time;
  if (name == "tremor_hz") return m.tremor_hz;
  if (name == "practice_rate") return m.practice_rate;
  throw std::logic_error("no motor parameter " + name);
}

void write_motor(util::JsonWriter& w, const MotorParameters& m) {
  w.begin_object()
      .field("reaction_mu", m.reaction_mu)
      .field("reaction_sigma", m.reaction_sigma)
      .field("reaction_tau", m.reaction_tau)
      .field("visual_delay", m.visual_delay)
      .field("fitts_a", m.fitts_a)
      .field("fitts_b", m.fitts_b)
      .field("noise_constant", m.noise_constant)
      .field("noise_proportional", m.noise_proportional)
      .field("aperture_intercept", m.aperture_intercept)
      .field("aperture_slope", m.aperture_slope)
      .field("peak_aperture_at", m.peak_aperture_at)
      .field("closing_time", m.closing_time)
      .field("tremor_hz", m.tremor_hz)
      .field("tremor_rms", m.tremor_rms)
      .field("tracker_jitter", m.tracker_jitter)
      .field("practice_rate", m.practice_rate)
      .field("practice_floor", m.practice_floor)
      .field("confirm_dwell", m.confirm_dwell)
      .field("regrasp_squeeze", m.regrasp_squeeze)
      .key("contact_rates")
      .begin_array()
      .value(m.contact_rates.retain_fast)
      .value(m.contact_rates.learn_fast)
      .value(m.contact_rates.retain_slow)
      .value(m.contact_rates.learn_slow)
      .end_array()
      .end_object();
}

// Every constant of the behaviour, in declaration order: the struct holds doubles only, so
// none can be left out of the hash.
void write_behaviour(util::JsonWriter& w, const Behaviour& b) {
  constexpr std::size_t n = sizeof(Behaviour) / sizeof(double);
  static_assert(sizeof(Behaviour) == n * sizeof(double), "Behaviour holds doubles only");
  const auto values = std::bit_cast<std::array<double, n>>(b);
  w.begin_array();
  for (double v : values) w.value(v);
  w.end_array();
}

}  // namespace

std::string model_parameters_json() {
  std::ostringstream out;
  util::JsonWriter w(out, 0);
  const Population p;
  w.begin_object().field("model", kParticipantModelVersion).key("population").begin_array();
  for (double v :
       {p.age_mean, p.age_sd, p.age_min, p.age_max, p.male_fraction, p.hand_length_mean,
        p.hand_length_sd, p.hand_length_min, p.hand_length_max, p.vr_experience_fraction})
    w.value(v);
  w.end_array().key("distributions").begin_array();
  for (const ParameterDistribution& d : motor_distributions())
    w.begin_array().value(d.name).value(d.mean).value(d.sd).value(d.low).value(d.high).end_array();
  w.end_array().key("defaults");
  write_motor(w, MotorParameters{});
  w.key("behaviour");
  write_behaviour(w, kBehaviour);
  w.end_object();
  return out.str();
}

std::string model_sha256() {
  return util::sha256_hex(model_parameters_json());
}

std::uint64_t person_seed(std::uint64_t seed, const std::string& id) {
  return util::fnv1a64(id) ^ (0x9E3779B97F4A7C15ull * (seed + 1));
}

MotorParameters draw_motor_parameters(std::uint64_t seed, const std::string& id) {
  // A stream of its own, apart from the covariates' (so adding a parameter here never moves
  // a person's age or hand length).
  MotorRandom r(person_seed(seed, id) ^ 0xD1B54A32D192ED03ull);
  MotorParameters m;
  for (const ParameterDistribution& d : motor_distributions())
    field(m, d.name) = d.sd > 0 ? r.truncated_normal(d.mean, d.sd, d.low, d.high)
                                : d.low + (d.high - d.low) * r.uniform();
  return m;
}

SimulatedPerson simulated_person(const store::Participant& participant, std::uint64_t seed) {
  SimulatedPerson person;
  person.participant = participant;
  person.motor = draw_motor_parameters(seed, participant.id);
  person.seed = person_seed(seed, participant.id);
  return person;
}

store::SimulatedPersonRow simulated_person_row(const SimulatedPerson& person, std::uint64_t seed) {
  std::ostringstream out;
  util::JsonWriter w(out, 0);
  write_motor(w, person.motor);
  return {person.participant.id, kParticipantModelVersion, model_sha256(), out.str(), seed};
}

SimulatedPerson draw_person(const Population& p, std::uint64_t seed, int index) {
  char id[16];
  std::snprintf(id, sizeof id, "S%02d", index + 1);
  MotorRandom r(person_seed(seed, id));
  store::Participant q;
  q.id = id;
  q.age = int(std::lround(r.truncated_normal(p.age_mean, p.age_sd, p.age_min, p.age_max)));
  q.sex = r.uniform() < p.male_fraction ? "M" : "F";
  q.handedness = "right";
  // Stored to the tenth of a millimetre, as a person's measurement is.
  q.hand_length = std::round(1e4 * r.truncated_normal(p.hand_length_mean, p.hand_length_sd,
                                                      p.hand_length_min, p.hand_length_max)) /
                  1e4;
  q.vr_experience = r.uniform() < p.vr_experience_fraction ? "yes" : "none";
  q.notes = std::string("simulated participant (") + kParticipantModelVersion + ", seed " +
            std::to_string(seed) + ")";
  q.simulated = true;
  return simulated_person(q, seed);
}

}  // namespace handlab::studies
