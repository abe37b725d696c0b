#include "studies/participant/participant_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <sstream>
#include <stdexcept>

#include "core/util/json_writer.h"
#include "core/util/portable_random.h"
#include "core/util/sha256.h"
#include "studies/participant/behaviour.h"
#include "studies/participant/motor_primitives.h"
#include "studies/participant/own_hand_posture.h"
#include "studies/participant/questionnaire_model.h"

namespace handlab::studies {

const char* const kParticipantModelVersion = "handlab participant model 2.7.1";

namespace {

// The motor parameters by name, in the order the record writes them (contact_rates apart).
constexpr std::pair<const char*, double MotorParameters::*> kMotorFields[] = {
    {"reaction_mu", &MotorParameters::reaction_mu},
    {"reaction_sigma", &MotorParameters::reaction_sigma},
    {"reaction_tau", &MotorParameters::reaction_tau},
    {"visual_delay", &MotorParameters::visual_delay},
    {"fitts_a", &MotorParameters::fitts_a},
    {"fitts_b", &MotorParameters::fitts_b},
    {"noise_constant", &MotorParameters::noise_constant},
    {"noise_proportional", &MotorParameters::noise_proportional},
    {"aperture_intercept", &MotorParameters::aperture_intercept},
    {"aperture_slope", &MotorParameters::aperture_slope},
    {"peak_aperture_at", &MotorParameters::peak_aperture_at},
    {"closing_time", &MotorParameters::closing_time},
    {"tremor_hz", &MotorParameters::tremor_hz},
    {"tremor_rms", &MotorParameters::tremor_rms},
    {"tracker_jitter", &MotorParameters::tracker_jitter},
    {"practice_rate", &MotorParameters::practice_rate},
    {"practice_floor", &MotorParameters::practice_floor},
    {"confirm_dwell", &MotorParameters::confirm_dwell},
    {"regrasp_squeeze", &MotorParameters::regrasp_squeeze},
    {"regrasp_lower", &MotorParameters::regrasp_lower},
    {"grip_retention", &MotorParameters::grip_retention},
    {"post_error_caution", &MotorParameters::post_error_caution},
};

// The behaviour's constants by name, every one in declaration order (checked against the
// struct's size: the struct holds doubles only, so none can be left out of the hash).
constexpr std::pair<const char*, double Behaviour::*> kBehaviourFields[] = {
    {"approach_height", &Behaviour::approach_height},
    {"lift_height", &Behaviour::lift_height},
    {"withdraw_height", &Behaviour::withdraw_height},
    {"place_depth", &Behaviour::place_depth},
    {"release_opening", &Behaviour::release_opening},
    {"slow_closing", &Behaviour::slow_closing},
    {"servo_gain", &Behaviour::servo_gain},
    {"max_corrections", &Behaviour::max_corrections},
    {"rest_travel", &Behaviour::rest_travel},
    {"rest_look", &Behaviour::rest_look},
    {"pre_contact_margin", &Behaviour::pre_contact_margin},
    {"closing_past_contact", &Behaviour::closing_past_contact},
    {"grip_loading", &Behaviour::grip_loading},
    {"tip_pinch_below", &Behaviour::tip_pinch_below},
    {"pad_on_face", &Behaviour::pad_on_face},
    {"caught_height", &Behaviour::caught_height},
    {"caught_look", &Behaviour::caught_look},
    {"wipe_depth", &Behaviour::wipe_depth},
    {"reopen_time", &Behaviour::reopen_time},
    {"reopen_rise_time", &Behaviour::reopen_rise_time},
    {"gain_min_aperture", &Behaviour::gain_min_aperture},
    {"gain_smoothing", &Behaviour::gain_smoothing},
    {"min_gain", &Behaviour::min_gain},
    {"min_tolerance", &Behaviour::min_tolerance},
    {"reach_tolerance_share", &Behaviour::reach_tolerance_share},
    {"centring_tolerance_share", &Behaviour::centring_tolerance_share},
    {"min_clearance", &Behaviour::min_clearance},
    {"loss_distance", &Behaviour::loss_distance},
    {"placement_tolerance", &Behaviour::placement_tolerance},
    {"placement_margin", &Behaviour::placement_margin},
    {"at_rest_over_floor", &Behaviour::at_rest_over_floor},
    {"home_height", &Behaviour::home_height},
    {"home_back", &Behaviour::home_back},
    {"rest_aperture", &Behaviour::rest_aperture},
    {"reference_hand_length", &Behaviour::reference_hand_length},
};
// The own hand's posture constants, every one (checked as the behaviour's are).
constexpr std::pair<const char*, double OwnHandPosture::*> kPostureFields[] = {
    {"pad_roll", &OwnHandPosture::pad_roll},
    {"tip_roll", &OwnHandPosture::tip_roll},
    {"tip_pitch", &OwnHandPosture::tip_pitch},
    {"tip_tilt", &OwnHandPosture::tip_tilt},
    {"others_curl_closed", &OwnHandPosture::others_curl_closed},
    {"others_curl_open", &OwnHandPosture::others_curl_open},
    {"others_open_at", &OwnHandPosture::others_open_at},
    {"pad_along", &OwnHandPosture::pad_along},
    {"aim_depth", &OwnHandPosture::aim_depth},
    {"tip_aim_along", &OwnHandPosture::tip_aim_along},
    {"tip_reach", &OwnHandPosture::tip_reach},
    {"aim_weight", &OwnHandPosture::aim_weight},
    {"widest_gap", &OwnHandPosture::widest_gap},
    {"gap_step", &OwnHandPosture::gap_step},
    {"keep_step", &OwnHandPosture::keep_step},
};
// The inverse kinematics' options: five doubles and the iteration count (padded to a double).
static_assert(sizeof(PinchIkOptions) == 6 * sizeof(double), "every IK option is written");
static_assert(std::size(kPostureFields) * sizeof(double) + sizeof(PinchIkOptions) ==
                  sizeof(OwnHandPosture),
              "every posture constant is named");
static_assert(sizeof(QuestionnaireWeights) == 4 * sizeof(double) &&
                  4 * sizeof(QuestionnaireWeights) + sizeof(double) == sizeof(QuestionnaireModel),
              "every questionnaire weight is written");
static_assert(std::size(kBehaviourFields) * sizeof(double) == sizeof(Behaviour),
              "every behaviour constant is named");
static_assert((std::size(kMotorFields) + 4) * sizeof(double) == sizeof(MotorParameters),
              "every motor parameter is named (the four rates apart)");

void write_motor(util::JsonWriter& w, const MotorParameters& m) {
  w.begin_object();
  for (const auto& [name, member] : kMotorFields) w.field(name, m.*member);
  w.key("contact_rates")
      .begin_array()
      .value(m.contact_rates.retain_fast)
      .value(m.contact_rates.learn_fast)
      .value(m.contact_rates.retain_slow)
      .value(m.contact_rates.learn_slow)
      .end_array()
      .end_object();
}

void write_behaviour(util::JsonWriter& w, const Behaviour& b) {
  w.begin_array();
  for (const auto& [name, member] : kBehaviourFields) w.value(b.*member);
  w.end_array();
}

void write_posture(util::JsonWriter& w, const OwnHandPosture& p) {
  w.begin_object();
  for (const auto& [name, member] : kPostureFields) w.field(name, p.*member);
  w.key("ik")
      .begin_array()
      .value(p.ik.root_weight)
      .value(p.ik.damping)
      .value(p.ik.max_step)
      .value(p.ik.translation_unit)
      .value(double(p.ik.iterations))
      .value(p.ik.step_tolerance)
      .end_array()
      .end_object();
}

void write_questionnaire(util::JsonWriter& w, const QuestionnaireModel& q) {
  w.begin_object();
  for (const auto& [name, weights] :
       {std::pair{"precision", q.precision}, std::pair{"ease", q.ease},
        std::pair{"naturalness", q.naturalness}, std::pair{"other", q.other}})
    w.key(name)
        .begin_array()
        .value(weights.attempt)
        .value(weights.correction)
        .value(weights.loss)
        .value(weights.doubling)
        .end_array();
  w.field("noise_sd", q.noise_sd).end_object();
}

}  // namespace

const ParticipantModel& frozen_participant_model() {
  // name, mean, sd, low, high (SI units; sources in docs/simulated-participants.md)
  static const ParticipantModel model = {
      {
          {"reaction_mu", 0.25, 0.03, 0.15, 0.40},
          {"visual_delay", 0.12, 0.02, 0.08, 0.18},
          {"fitts_a", 0.55, 0.10, 0.30, 0.90},
          {"fitts_b", 0.41, 0.05, 0.25, 0.60},
          {"aperture_intercept", 0.050, 0.008, 0.030, 0.070},
          {"closing_time", 0.50, 0.08, 0.30, 0.80},
          {"tremor_hz", 10.0, 0.0, 8.0, 12.0},
          {"practice_rate", 0.35, 0.10, 0.10, 0.70},
      },
      MotorParameters{},
      Behaviour{},
  };
  return model;
}

ParticipantModel changed_model(ParticipantModel model,
                               const std::vector<std::pair<std::string, double>>& changes) {
  for (const auto& [name, value] : changes) {
    if (!std::isfinite(value))
      throw std::invalid_argument("model parameter " + name + ": not a finite number");
    bool found = false;
    for (ParameterDistribution& d : model.distributions)
      if (d.name == name) {
        // The bounds move with the mean, so that the truncation shapes it as before.
        d.low += value - d.mean;
        d.high += value - d.mean;
        d.mean = value;
        found = true;
      }
    for (const auto& [field, member] : kMotorFields)
      if (!found && field == name) {
        model.fixed.*member = value;
        found = true;
      }
    for (const auto& [field, member] : kBehaviourFields)
      if (!found && field == name) {
        model.behaviour.*member = value;
        found = true;
      }
    if (!found) throw std::invalid_argument("the participant model has no parameter " + name);
  }
  return model;
}

std::vector<std::pair<std::string, double>> model_parameters(const ParticipantModel& model) {
  std::vector<std::pair<std::string, double>> out;
  for (const ParameterDistribution& d : model.distributions) out.emplace_back(d.name, d.mean);
  for (const auto& [name, member] : kMotorFields) {
    const bool drawn = std::any_of(model.distributions.begin(), model.distributions.end(),
                                   [&](const ParameterDistribution& d) { return d.name == name; });
    if (!drawn) out.emplace_back(name, model.fixed.*member);
  }
  for (const auto& [name, member] : kBehaviourFields)
    out.emplace_back(name, model.behaviour.*member);
  return out;
}

std::string model_parameters_json(const ParticipantModel& model) {
  std::ostringstream out;
  util::JsonWriter w(out, 0);
  const Population p;
  w.begin_object().field("model", kParticipantModelVersion).key("population").begin_array();
  for (double v :
       {p.age_mean, p.age_sd, p.age_min, p.age_max, p.male_fraction, p.hand_length_mean,
        p.hand_length_sd, p.hand_length_min, p.hand_length_max, p.vr_experience_fraction})
    w.value(v);
  w.end_array().key("distributions").begin_array();
  for (const ParameterDistribution& d : model.distributions)
    w.begin_array().value(d.name).value(d.mean).value(d.sd).value(d.low).value(d.high).end_array();
  w.end_array().key("defaults");
  write_motor(w, model.fixed);
  w.key("behaviour");
  write_behaviour(w, model.behaviour);
  // Since 2.7.1: the own hand's postures and the questionnaire's weights, as the code reads
  // them (not settable: what 2.7 ran, hashed).
  w.key("own_hand");
  write_posture(w, OwnHandPosture{});
  w.key("questionnaire");
  write_questionnaire(w, QuestionnaireModel{});
  w.end_object();
  return out.str();
}

std::string model_sha256(const ParticipantModel& model) {
  return util::sha256_hex(model_parameters_json(model));
}

std::uint64_t person_seed(std::uint64_t seed, const std::string& id) {
  return util::fnv1a64(id) ^ (0x9E3779B97F4A7C15ull * (seed + 1));
}

MotorParameters draw_motor_parameters(std::uint64_t seed, const std::string& id,
                                      const ParticipantModel& model) {
  // A stream of its own, apart from the covariates' (so adding a parameter here never moves
  // a person's age or hand length).
  MotorRandom r(person_seed(seed, id) ^ 0xD1B54A32D192ED03ull);
  MotorParameters m = model.fixed;
  for (const ParameterDistribution& d : model.distributions) {
    const auto at = std::find_if(std::begin(kMotorFields), std::end(kMotorFields),
                                 [&](const auto& f) { return d.name == std::string(f.first); });
    if (at == std::end(kMotorFields))
      throw std::logic_error(std::string("no motor parameter ") + d.name);
    m.*(at->second) = d.sd > 0 ? r.truncated_normal(d.mean, d.sd, d.low, d.high)
                               : d.low + (d.high - d.low) * r.uniform();
  }
  return m;
}

SimulatedPerson simulated_person(const store::Participant& participant, std::uint64_t seed,
                                 const ParticipantModel& model) {
  SimulatedPerson person;
  person.participant = participant;
  person.motor = draw_motor_parameters(seed, participant.id, model);
  person.behaviour = model.behaviour;
  person.seed = person_seed(seed, participant.id);
  return person;
}

store::SimulatedPersonRow simulated_person_row(const SimulatedPerson& person, std::uint64_t seed,
                                               const ParticipantModel& model) {
  std::ostringstream out;
  util::JsonWriter w(out, 0);
  write_motor(w, person.motor);
  return {person.participant.id, kParticipantModelVersion, model_sha256(model), out.str(), seed};
}

std::string simulated_participant_id(int index) {
  char id[16];
  std::snprintf(id, sizeof id, "S%02d", index + 1);
  return id;
}

SimulatedPerson draw_person(const Population& p, std::uint64_t seed, int index,
                            const ParticipantModel& model) {
  const std::string id = simulated_participant_id(index);
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
  return simulated_person(q, seed, model);
}

}  // namespace handlab::studies
