// A simulated person: covariates stored like a real participant's, and the motor parameters of
// the model, drawn once from stated population distributions (every distribution and its
// source: docs/simulated-participants.md). The model is frozen by its version and the hash of
// its parameters (model_sha256), stored with every simulated participant.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/store/study_store.h"
#include "studies/participant/behaviour.h"
#include "studies/participant/two_rate_adaptation.h"

namespace handlab::studies {

struct MotorParameters {
  double reaction_mu = 0.25, reaction_sigma = 0.03, reaction_tau = 0.10;  // s, ex-Gaussian
  double visual_delay = 0.12;                                             // s
  double fitts_a = 0.55, fitts_b = 0.41;                                  // s, s/bit
  double noise_constant = 0.0005;    // m: endpoint SD per axis, constant part
  double noise_proportional = 0.02;  // endpoint SD per metre moved
  // m: peak aperture = this (scaled by hand length) + slope * object size
  double aperture_intercept = 0.050;
  double aperture_slope = 0.54;
  double peak_aperture_at = 0.65;                 // fraction of the reach
  double closing_time = 0.50;                     // s
  double tremor_hz = 10.0, tremor_rms = 0.00005;  // physiological tremor at the hand
  double tracker_jitter = 0.000063;               // m per axis and joint (measured, data/leap)
  double practice_rate = 0.35;   // per trial counted: durations' exponential law of practice
  double practice_floor = 0.60;  // the share of a duration practice leaves
  double confirm_dwell = 0.15;   // s seeing both pads on the cube before lifting
  // After each slip under load: m more loading after contact (pads that let the cube go), or
  // m lower on the cube (pads that slid over it).
  double regrasp_squeeze = 0.003;
  double regrasp_lower = 0.0025;
  double grip_retention = 0.9;  // share of what slips taught kept over a trial without one
  // The share of practice's speed-up of the grasp (closing, loading, lift) each failed grasp
  // gives back: 1, the next grasp at its unpractised pace.
  double post_error_caution = 1.0;
  // Trial-by-trial adaptation of where it expects its pads to meet the cube.
  TwoRateRates contact_rates{0.59, 0.21, 0.992, 0.02};
};

struct SimulatedPerson {
  store::Participant participant;  // id, age, sex, handedness, hand length, VR experience
  MotorParameters motor;
  Behaviour behaviour;     // the model's, the same for everyone
  std::uint64_t seed = 0;  // the person's own stream (trials draw from it with their place)
};

// The population the study's participants are drawn from (the ISMAR 2021 sample).
struct Population {
  double age_mean = 26.2, age_sd = 4.04, age_min = 18, age_max = 34;
  double male_fraction = 0.75;
  double hand_length_mean = 0.188, hand_length_sd = 0.0123;
  double hand_length_min = 0.159, hand_length_max = 0.205;
  double vr_experience_fraction = 0.5;
};

// A per-person parameter's distribution: normal, redrawn inside [low, high].
struct ParameterDistribution {
  const char* name;
  double mean, sd, low, high;
};

// The model: the per-person distributions (in drawing order: a new one goes last, so that
// adding it never moves the others' draws), the motor parameters not drawn, the behaviour.
struct ParticipantModel {
  std::vector<ParameterDistribution> distributions;
  MotorParameters fixed;
  Behaviour behaviour;
};

// The model as its version names it (kParticipantModelVersion).
const ParticipantModel& frozen_participant_model();

// The model with parameters changed by name, for a sensitivity analysis: a per-person
// parameter's name changes its distribution's mean (kept inside its bounds' span), a fixed
// motor parameter's or a behaviour constant's its value. Throws std::invalid_argument on a
// name the model lacks.
ParticipantModel changed_model(ParticipantModel model,
                               const std::vector<std::pair<std::string, double>>& changes);
// Every name changed_model takes, with its value in `model`.
std::vector<std::pair<std::string, double>> model_parameters(const ParticipantModel& model);

// The model's version, and the SHA-256 of everything that decides what its people do: the
// population, the per-person distributions, the fixed motor parameters and the behaviour's
// constants (model_parameters_json). Printed by `simulate`, stored with each participant.
extern const char* const kParticipantModelVersion;
std::string model_parameters_json(const ParticipantModel& model = frozen_participant_model());
std::string model_sha256(const ParticipantModel& model = frozen_participant_model());

// The id of person `index` (0-based): "S01", "S02", ...
std::string simulated_participant_id(int index);

// Person `index` (0-based) of the population under `seed`: covariates and motor parameters.
// The id is simulated_participant_id(index); the notes mark the participant as simulated.
SimulatedPerson draw_person(const Population& population, std::uint64_t seed, int index,
                            const ParticipantModel& model = frozen_participant_model());

// The motor parameters of a participant with a given id (e.g. one enrolled by hand and run
// with `session run --tracker simulated`): drawn from the population under `seed` and the id.
MotorParameters draw_motor_parameters(std::uint64_t seed, const std::string& id,
                                      const ParticipantModel& model = frozen_participant_model());

// A person from its stored covariates, with the motor parameters of its id under `seed`.
SimulatedPerson simulated_person(const store::Participant& participant, std::uint64_t seed,
                                 const ParticipantModel& model = frozen_participant_model());

// What the study database keeps of a simulated person (store::SimulatedPersonRow).
store::SimulatedPersonRow simulated_person_row(
    const SimulatedPerson& person, std::uint64_t seed,
    const ParticipantModel& model = frozen_participant_model());

// The seed of a person's own stream from the population seed and the id.
std::uint64_t person_seed(std::uint64_t seed, const std::string& id);

}  // namespace handlab::studies
