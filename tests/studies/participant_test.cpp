// The simulated participant: its motor primitives, its population, the tracker jitter it adds
// (measured from the Leap recordings), its blindness to the condition, what it does with a cube
// caught on its hand, and its questionnaire.
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <optional>
#include <set>

#include <gtest/gtest.h>

#include "core/hand/flesh.h"
#include "core/hand/simulated_hand.h"
#include "core/retarget/retargeter.h"
#include "core/sim/hand_sim_model.h"
#include "core/task/cube_task.h"
#include "core/task/grasp_proxy.h"
#include "core/task/soft_hand_world.h"
#include "core/tracking/hand_fitting.h"
#include "core/tracking/recording_io.h"
#include "studies/participant/motor_primitives.h"
#include "studies/participant/own_hand.h"
#include "studies/participant/participant_model.h"
#include "studies/participant/questionnaire_model.h"
#include "studies/participant/simulated_participant.h"
#include "studies/participant/tracking_jitter.h"
#include "studies/session/session_runner.h"
#include "studies/session/trial_driver.h"

namespace handlab::studies {
namespace {

const std::string kSource = HANDLAB_SOURCE_DIR;

// The participant of a trial as the simulated tracker builds it (simulated_source.cpp): from who it
// is, what it sees of the trial (seen_trial_of, the one reduction of a condition) and what it
// remembers.
std::unique_ptr<SimulatedParticipant> participant_for(const TrialSetup& setup, std::uint64_t seed,
                                                      const OwnHand& own,
                                                      const ParticipantMemory& memory = {}) {
  return std::make_unique<SimulatedParticipant>(simulated_person(setup.participant, seed), own,
                                                seen_trial_of(setup, 120.0), memory);
}

TEST(MotorPrimitives, MinimumJerkAndFitts) {
  EXPECT_EQ(minimum_jerk(0.0), 0.0);
  EXPECT_EQ(minimum_jerk(1.0), 1.0);
  EXPECT_NEAR(minimum_jerk(0.5), 0.5, 1e-15);
  for (double u : {0.1, 0.3, 0.45}) EXPECT_NEAR(minimum_jerk(u) + minimum_jerk(1 - u), 1.0, 1e-12);
  // Zero velocity at both ends: the profile is flat there.
  EXPECT_LT(minimum_jerk(1e-3), 1e-7);
  EXPECT_EQ(minimum_jerk(-1.0), 0.0);
  EXPECT_EQ(minimum_jerk(2.0), 1.0);
  // a + b log2(2D/W); an index of difficulty under one bit counts one.
  EXPECT_NEAR(fitts_time(0.5, 0.4, 0.2, 0.01), 0.5 + 0.4 * std::log2(40.0), 1e-12);
  EXPECT_NEAR(fitts_time(0.5, 0.4, 0.001, 0.06), 0.9, 1e-12);
  MinimumJerkMove move{Eigen::Vector3d::Zero(), Eigen::Vector3d(0.1, 0, 0), 1.0, 0.5};
  EXPECT_EQ(move.at(0.5), Eigen::Vector3d::Zero());
  EXPECT_NEAR(move.at(1.25).x(), 0.05, 1e-15);
  EXPECT_EQ(move.at(2.0), Eigen::Vector3d(0.1, 0, 0));
  EXPECT_FALSE(move.done(1.4));
  EXPECT_TRUE(move.done(1.5));
}

// The ex-Gaussian's mean is mu + tau and its variance sigma^2 + tau^2; the sample moments of
// 40,000 draws are within 5 standard errors.
TEST(MotorPrimitives, ExGaussianMoments) {
  MotorRandom random(7);
  const double mu = 0.25, sigma = 0.03, tau = 0.10;
  const int n = 40000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = random.ex_gaussian(mu, sigma, tau);
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / n, variance = sum2 / n - mean * mean;
  const double sd = std::sqrt(sigma * sigma + tau * tau);
  EXPECT_NEAR(mean, mu + tau, 5 * sd / std::sqrt(n));
  // The variance's SE: sqrt((m4 - s^4) / n); for the exponential part m4 = 9 tau^4.
  EXPECT_NEAR(variance, sd * sd,
              5 * std::sqrt((9 * std::pow(tau, 4) + 3 * std::pow(sigma, 4)) / n));
  double lowest = 1.0;
  MotorRandom again(7);
  for (int i = 0; i < 1000; ++i) lowest = std::min(lowest, again.truncated_normal(0, 1, -0.5, 0.5));
  EXPECT_GE(lowest, -0.5);
}

// The default tracking jitter is the one measured on the recording of a hand held still
// (confidence2), and the still pinch recordings jitter less (the default is an upper bound).
TEST(TrackingJitter, DefaultIsMeasuredFromTheLeapRecordings) {
  const MotorParameters defaults;
  const TrackingJitter still = measure_tracking_jitter(
      tracking::read_recording(kSource + "/data/leap/confidence2.json.lz").frames);
  EXPECT_GT(still.samples, 1000);
  EXPECT_NEAR(still.sd, defaults.tracker_jitter, 0.0000015);
  for (const char* name : {"pinch.json.lz", "pinch-57fps.json.lz", "grab.json.lz"}) {
    const TrackingJitter j =
        measure_tracking_jitter(tracking::read_recording(kSource + "/data/leap/" + name).frames);
    EXPECT_GT(j.samples, 100) << name;
    EXPECT_GT(j.sd, 0.0) << name;
    EXPECT_LE(j.sd, defaults.tracker_jitter) << name;
  }
}

TEST(Population, DrawsTheStudySampleDeterministically) {
  const Population population;
  std::set<std::string> ids;
  double male = 0, length_sum = 0;
  const int n = 400;
  for (int i = 0; i < n; ++i) {
    const SimulatedPerson p = draw_person(population, 11, i);
    ids.insert(p.participant.id);
    EXPECT_TRUE(p.participant.simulated);
    EXPECT_GE(p.participant.age, 18);
    EXPECT_LE(p.participant.age, 34);
    EXPECT_GE(p.participant.hand_length, 0.159);
    EXPECT_LE(p.participant.hand_length, 0.205);
    male += p.participant.sex == "M";
    length_sum += p.participant.hand_length;
    const SimulatedPerson again = draw_person(population, 11, i);
    EXPECT_EQ(again.participant.hand_length, p.participant.hand_length);
    EXPECT_EQ(again.motor.fitts_b, p.motor.fitts_b);
    EXPECT_EQ(again.seed, p.seed);
  }
  EXPECT_EQ(int(ids.size()), n);
  EXPECT_NEAR(male / n, population.male_fraction, 5 * std::sqrt(0.75 * 0.25 / n));
  EXPECT_NEAR(length_sum / n, population.hand_length_mean, 0.003);
  EXPECT_NE(draw_person(population, 12, 0).participant.hand_length,
            draw_person(population, 11, 0).participant.hand_length);
}

// Its questionnaire answers follow what it experienced, never the condition (the function
// has no condition to read): a clean trial rates higher than a trial of repeated failures.
// The frozen model's version and hash, as docs/simulated-participants.md records them: a
// constant the model reads that changes changes the hash, and this test with it.
TEST(ParticipantModel, TheFrozenModelIsItsVersionAndHash) {
  EXPECT_STREQ(kParticipantModelVersion, "handlab participant model 2.7.1");
  EXPECT_EQ(model_sha256(), "031e128532017b0feb16175b881a0df9f940720dd809b7f415febbb73b6a5ee5");
  EXPECT_NE(model_parameters_json(frozen_participant_model()).find("\"keep_step\""),
            std::string::npos);
}

TEST(QuestionnaireModel, AnswersFollowTheExperience) {
  const std::vector<std::string> ids = {"precision", "ease", "naturalness"};
  TrialExperience clean{1, 0, 0, 6.0};
  TrialExperience troubled{4, 5, 2, 6.0};
  double clean_sum = 0, troubled_sum = 0;
  for (std::uint64_t s = 0; s < 200; ++s) {
    for (int v : simulated_answers(ids, 5, clean, 6.0, s)) {
      EXPECT_GE(v, 1);
      EXPECT_LE(v, 5);
      clean_sum += v;
    }
    for (int v : simulated_answers(ids, 5, troubled, 24.0, s)) troubled_sum += v;
  }
  EXPECT_GT(clean_sum / 600, troubled_sum / 600 + 1.0);
  EXPECT_EQ(simulated_answers(ids, 5, clean, 6.0, 3), simulated_answers(ids, 5, clean, 6.0, 3));
}

// One trial in closed loop on the grasp proxy: what the display showed after every step and
// what the participant sent.
struct ClosedLoop {
  std::vector<Observation> shown;
  std::vector<tracking::TrackedFrame> sent;
  std::vector<double> own_aperture;       // per frame sent
  std::vector<Eigen::Vector3d> own_grip;  // per frame sent
  bool success = false;
};

// Drives `world` with the participant's frames (retargeted by `strategy`) until the task ends
// or `limit` seconds pass (a trial's timeout), recording what it saw, sent and which phases it
// went through.
ClosedLoop drive(SimulatedParticipant& participant, task::HandCubeWorld& world,
                 const TrialSetup& setup, retarget::Strategy strategy, double limit,
                 std::set<std::string>* phases = nullptr, double rest_time = 0.5) {
  const hand::Skeleton sim = hand::build_simulated_hand(setup.condition.simulated_hand);
  task::SceneLayout layout = setup.protocol->scene;
  layout.cube_size = setup.condition.cube_size;
  std::optional<tracking::TrackedHandFitter> fitter;
  if (strategy == retarget::Strategy::kNaive)
    fitter.emplace(setup.participant.hand_length, tracking::Side::kRight);
  retarget::Retargeter retargeter(strategy, sim, setup.calibration, fitter);
  task::TaskSettings task_settings;
  task_settings.layout = layout;
  task_settings.timeout = limit;
  task_settings.rest_time = rest_time;
  task::CubeTask task(task_settings);
  task.start(0.0);
  ClosedLoop loop;
  loop.shown.push_back(display_observation(world, layout, 0.0));
  for (long step = 1; !task.finished(); ++step) {
    const double t = double(step) / 120.0;
    loop.sent.push_back(participant.act(loop.shown.back()));
    if (phases) phases->insert(participant.phase_name());
    loop.own_aperture.push_back(participant.own_aperture());
    loop.own_grip.push_back(participant.own_grip());
    const hand::HandPose pose = retargeter.retarget(loop.sent.back().hands.at(0)).pose;
    world.step(&pose, 1.0 / 120.0);
    task.update(task::observe_task(world, t));
    loop.shown.push_back(display_observation(world, layout, t));
  }
  loop.success = task.phase() == task::TaskPhase::kDone;
  return loop;
}

ClosedLoop run_closed_loop(SimulatedParticipant& participant, const TrialSetup& setup) {
  const hand::Skeleton sim = hand::build_simulated_hand(setup.condition.simulated_hand);
  task::SceneLayout layout = setup.protocol->scene;
  layout.cube_size = setup.condition.cube_size;
  task::GraspProxySettings settings;
  settings.cube_size = layout.cube_size;
  task::GraspProxyWorld world(sim, settings, task::cube_start_pose(layout).translation());
  return drive(participant, world, setup, retarget::Strategy::kOurs, setup.protocol->timeout_s);
}

// A person's trial at `position` in each of the conditions of one cube size (the strategies'),
// as the session runner sets them up.
std::vector<TrialSetup> setups_of_cube(const Protocol& protocol, const SimulatedPerson& person,
                                       double cube, int position,
                                       const retarget::Calibration& calibration) {
  std::vector<TrialSetup> setups;
  for (const Condition& c : protocol.conditions())
    if (c.cube_size == cube) {
      TrialSetup s;
      s.protocol = &protocol;
      s.condition = c;
      s.participant = person.participant;
      s.planned.position = position;
      s.calibration = calibration;
      setups.push_back(s);
    }
  return setups;
}

// Person `who` of population seed 5 in the study's protocol: their own hand and calibration.
struct StudyPerson {
  explicit StudyPerson(int who)
      : protocol(read_protocol(kSource + "/studies/fine-manipulation-2021.json")),
        driver(simulated_tracker(5)),
        person(draw_person(Population{}, 5, who)),
        own(person.participant.hand_length),
        calibration(driver.calibrate(protocol, person.participant)) {}
  const Protocol protocol;
  PipelineTrialDriver driver;
  const SimulatedPerson person;
  const OwnHand own;
  const retarget::Calibration calibration;
};

// A memory of `trials` trials, all with one cube.
ParticipantMemory memory_of_cube(double cube, int trials) {
  ParticipantMemory memory;
  memory.trials = trials;
  CubeMemory remembered;
  remembered.cube_size = cube;
  remembered.trials = trials;
  memory.cubes.push_back(remembered);
  return memory;
}

// The blinding test: participants built for the same person and trial place in conditions
// that differ only in the strategy (its label and its flag), fed the same observations, send
// the same frames, bit for bit. The model cannot branch on the label: nothing of it reaches
// the participant but what seen_trial_of gives (SeenTrial).
TEST(SimulatedParticipantBlinding, SameObservationsSameFramesWhateverTheStrategy) {
  const StudyPerson p(3);
  for (double cube : {0.06, 0.01}) {
    const std::vector<TrialSetup> setups =
        setups_of_cube(p.protocol, p.person, cube, 7, p.calibration);
    ASSERT_EQ(setups.size(), 2u);
    ASSERT_NE(setups[0].condition.strategy.method, setups[1].condition.strategy.method);
    ASSERT_NE(setups[0].condition.label, setups[1].condition.label);
    auto first = participant_for(setups[0], 5, p.own);
    const ClosedLoop loop = run_closed_loop(*first, setups[0]);
    EXPECT_TRUE(loop.success) << cube;
    EXPECT_GT(first->experience().grasp_attempts, 0);
    auto second = participant_for(setups[1], 5, p.own);
    ASSERT_GT(loop.sent.size(), 120u);
    for (std::size_t k = 0; k < loop.sent.size(); ++k) {
      const tracking::TrackedFrame f = second->act(loop.shown[k]);
      const auto& a = loop.sent[k].hands.at(0).joints;
      const auto& b = f.hands.at(0).joints;
      for (int d = 0; d < 5; ++d)
        for (int j = 0; j < 5; ++j)
          ASSERT_EQ(a[std::size_t(d)][std::size_t(j)], b[std::size_t(d)][std::size_t(j)])
              << "cube " << cube << " frame " << k;
    }
    EXPECT_EQ(second->experience().grasp_attempts, first->experience().grasp_attempts);
    EXPECT_EQ(second->experience().corrections, first->experience().corrections);
    // And the observations matter: a cube seen elsewhere changes what it sends.
    auto third = participant_for(setups[1], 5, p.own);
    bool differs = false;
    for (std::size_t k = 0; k < loop.sent.size() && !differs; ++k) {
      Observation o = loop.shown[k];
      o.cube_position.z() += 0.02;
      differs = third->act(o).hands.at(0).joints != loop.sent[k].hands.at(0).joints;
    }
    EXPECT_TRUE(differs);
  }
}

// The simulated people's reach-to-grasp beside published human kinematics (the table in
// docs/simulated-participants.md, "Kinematics"): over cubes of 2 to 6 cm (the pad pinch) on
// the grasp proxy, each person's first reach, measured from its own hand's trajectory:
// - the peak grip aperture against the object's size: slope within 0.54 +- 2 x 0.04 (real
//   objects, Cuijpers et al. 2006);
// - the time of peak aperture within 55-80 % of the reach (two-thirds: Hu et al. 2005;
//   closing with the low-velocity phase at about 75 %: Jeannerod 1984);
// - the reach's movement time against its index of difficulty: slope and intercept within the
//   range of the VR regressions (b 0.25-0.65 s/bit, a 0.2-1.15 s: Fig. 6a of "Metrics for 3D
//   Object Pointing and Manipulation in Virtual Reality", IEEE RAM 2022).
TEST(SimulatedParticipantKinematics, ReachAndGraspWithinPublishedRanges) {
  const Protocol protocol = read_protocol(kSource + "/studies/fine-manipulation-2021.json");
  PipelineTrialDriver driver(simulated_tracker(5));
  Condition base;
  for (const Condition& c : protocol.conditions())
    if (c.strategy.method == retarget::Strategy::kOurs && c.cube_size == 0.06) base = c;
  auto fit = [](const std::vector<double>& x, const std::vector<double>& y) {
    const double n = double(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
    }
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    return std::pair{slope, (sy - slope * sx) / n};
  };
  std::vector<double> slopes, intercepts;  // each person's reach time against ID
  double least_share = 1.0, most_share = 0.0;
  for (int who : {0, 2, 4, 6, 8, 10}) {
    const SimulatedPerson person = draw_person(Population{}, 5, who);
    const OwnHand own(person.participant.hand_length);
    TrialSetup setup;
    setup.protocol = &protocol;
    setup.participant = person.participant;
    setup.calibration = driver.calibrate(protocol, person.participant);
    std::vector<double> sizes, peaks, ids, times;
    for (double size : {0.02, 0.03, 0.04, 0.05, 0.06}) {
      setup.condition = base;
      setup.condition.cube_size = size;
      auto participant = participant_for(setup, 5, own);
      const ClosedLoop loop = run_closed_loop(*participant, setup);
      // The reach, as kinematic studies mark it: from the hand's speed first exceeding 5 % of
      // the reach's peak speed to its falling below that again.
      std::vector<double> speed(loop.own_grip.size(), 0.0);
      for (std::size_t k = 1; k < speed.size(); ++k)
        speed[k] = (loop.own_grip[k] - loop.own_grip[k - 1]).norm() * 120.0;
      // (The reach is the fastest movement of the trial's first 2.5 s.)
      const double peak_speed = *std::max_element(speed.begin(), speed.begin() + 300);
      std::size_t start = 0, end = 0;
      for (std::size_t k = 1; k < speed.size(); ++k) {
        if (start == 0 && speed[k] > 0.05 * peak_speed) start = k - 1;
        if (start > 0 && k > start + 12 && speed[k] < 0.05 * peak_speed) {
          end = k;
          break;
        }
      }
      ASSERT_GT(end, start) << size;
      std::size_t at_peak = start;
      for (std::size_t k = start; k <= end; ++k)
        if (loop.own_aperture[k] > loop.own_aperture[at_peak] + 1e-6) at_peak = k;
      const double share = double(at_peak - start) / double(end - start);
      least_share = std::min(least_share, share);
      most_share = std::max(most_share, share);
      EXPECT_GT(share, 0.55) << who << " " << size;
      EXPECT_LT(share, 0.80) << who << " " << size;
      const double distance = (loop.own_grip[end] - loop.own_grip[start]).norm();
      const double width = loop.own_aperture[at_peak] - size;  // the pads' clearance
      sizes.push_back(size);
      peaks.push_back(loop.own_aperture[at_peak]);
      ids.push_back(std::log2(2 * distance / width));
      times.push_back(double(end - start) / 120.0);
    }
    const auto [aperture_slope, aperture_intercept] = fit(sizes, peaks);
    EXPECT_GT(aperture_slope, 0.46) << who;
    EXPECT_LT(aperture_slope, 0.62) << who;
    EXPECT_GT(aperture_intercept, 0.02) << who;
    EXPECT_LT(aperture_intercept, 0.08) << who;
    std::cout << person.participant.id << ": peak aperture " << aperture_intercept << " + "
              << aperture_slope << " size\n";
    const auto [b, a] = fit(ids, times);
    slopes.push_back(b);
    intercepts.push_back(a);
  }
  // The people's median (one person's fit over an ID range of about a bit is noisy).
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return 0.5 * (v[(v.size() - 1) / 2] + v[v.size() / 2]);
  };
  const double b = median(slopes), a = median(intercepts);
  std::cout << "reach time " << a << " + " << b << " ID (medians over people); peak aperture at "
            << least_share << " to " << most_share << " of the reach\n";
  EXPECT_GT(b, 0.25);
  EXPECT_LT(b, 0.65);
  EXPECT_GT(a, 0.2);
  EXPECT_LT(a, 1.15);
}

// A world whose cube sticks to the virtual thumb's tip when the tip comes up from it (as a
// cube caught in the flesh does), until the tip presses it 5 mm into the floor: the hand's bones
// are the grasp proxy's (the participant's own motion, retargeted), the cube is the test's.
class CaughtCubeWorld : public task::HandCubeWorld {
 public:
  CaughtCubeWorld(const hand::Skeleton& sim, const task::SceneLayout& layout)
      : proxy_(sim, proxy_settings(layout.cube_size), Eigen::Vector3d(0.3, 0.1, 0.3)),
        thumb_(sim.bone_index("thumb3")),
        length_(sim.bones[std::size_t(thumb_)].length),
        half_(layout.cube_size / 2) {
    cube_.position = layout.zone_a + Eigen::Vector3d(0, half_, 0);
  }
  void step(const hand::HandPose* target, double dt) override {
    proxy_.step(target, dt);
    if (proxy_.bones().empty()) return;
    const Eigen::Isometry3d& bone = proxy_.bones()[std::size_t(thumb_)];
    const Eigen::Vector3d tip = bone.translation() + length_ * bone.linear().col(1);
    // Caught when the tip, at the cube, comes up 5 mm from the lowest it went there.
    const bool near = (tip - cube_.position).norm() < 0.025;
    lowest_ = near ? std::min(lowest_, tip.y()) : INFINITY;
    if (!caught_ && !freed_ && near && tip.y() > lowest_ + 0.005) {
      caught_ = true;
      offset_ = cube_.position - tip;
    }
    if (!caught_) return;
    cube_.position = tip + offset_;
    highest_caught_ = std::max(highest_caught_, cube_.position.y());
    if (cube_.position.y() < half_ - 0.005) {  // pressed into the floor: it strips it off
      cube_.position.y() = half_;
      caught_ = false;
      freed_ = true;
    }
  }
  const task::CubeState& cube() const override { return cube_; }
  bool thumb_contact() const override { return caught_; }
  bool index_contact() const override { return false; }
  const std::vector<Eigen::Isometry3d>& bones() const override { return proxy_.bones(); }
  bool freed() const { return freed_; }
  double highest_caught() const { return highest_caught_; }

 private:
  static task::GraspProxySettings proxy_settings(double cube_size) {
    task::GraspProxySettings s;
    s.cube_size = cube_size;
    return s;
  }
  task::GraspProxyWorld proxy_;  // its own cube out of the way: the hand's bones alone
  int thumb_;
  double length_, half_;
  bool caught_ = false, freed_ = false;
  double highest_caught_ = 0.0, lowest_ = INFINITY;
  Eigen::Vector3d offset_ = Eigen::Vector3d::Zero();
  task::CubeState cube_;
};

// The grasp proxy with what the participant sees changed, to force the model's every path:
// contact hidden until the closing is over (a slow close, then a re-grasp), or the cube shown
// dropping out of the hand once it is first lifted 4 cm (a lost cube, re-grasps, the trial
// cut by its time limit), the pads closing where it was or, with kDropPadsApart, the thumb
// shown 3 cm further from the index from then on (pads that stayed apart).
class SeenOtherwiseWorld : public task::HandCubeWorld {
 public:
  enum class Twist { kHideContact, kDropOnce, kDropPadsApart };
  SeenOtherwiseWorld(const hand::Skeleton& sim, const task::SceneLayout& layout, Twist twist)
      : proxy_(sim, settings(layout.cube_size), task::cube_start_pose(layout).translation()),
        twist_(twist),
        half_(0.5 * layout.cube_size),
        thumb_tip_(sim.bone_index("thumb3")),
        index_tip_(sim.bone_index("index3")) {
    for (int b = 0; b < int(sim.bones.size()); ++b)
      if (sim.bones[b].name.rfind("thumb", 0) == 0) thumb_bones_.push_back(b);
  }
  void step(const hand::HandPose* target, double dt) override {
    proxy_.step(target, dt);
    time_ += dt;
    cube_ = proxy_.cube();
    const bool touching = proxy_.thumb_contact() && proxy_.index_contact();
    if (twist_ == Twist::kHideContact) {
      if (touching && touching_since_ < 0) touching_since_ = time_;
      hidden_ = touching && time_ - touching_since_ < 1.5;
    } else {
      if (!dropped_at_ && cube_.position.y() > half_ + 0.04) dropped_at_ = cube_.position;
      if (dropped_at_) {
        cube_.position = Eigen::Vector3d(dropped_at_->x(), half_, dropped_at_->z());
        hidden_ = true;
      }
    }
    bones_ = proxy_.bones();
    if (twist_ == Twist::kDropPadsApart && dropped_at_) {
      const Eigen::Vector3d apart =
          (bones_[thumb_tip_].translation() - bones_[index_tip_].translation()).normalized();
      for (int b : thumb_bones_) bones_[b].pretranslate(0.03 * apart);
    }
  }
  const task::CubeState& cube() const override { return cube_; }
  bool thumb_contact() const override { return !hidden_ && proxy_.thumb_contact(); }
  bool index_contact() const override { return !hidden_ && proxy_.index_contact(); }
  const std::vector<Eigen::Isometry3d>& bones() const override { return bones_; }

 private:
  static task::GraspProxySettings settings(double cube_size) {
    task::GraspProxySettings s;
    s.cube_size = cube_size;
    return s;
  }
  task::GraspProxyWorld proxy_;
  Twist twist_;
  double half_, time_ = 0.0, touching_since_ = -1.0;
  bool hidden_ = false;
  std::optional<Eigen::Vector3d> dropped_at_;
  task::CubeState cube_;
  int thumb_tip_, index_tip_;
  std::vector<int> thumb_bones_;
  std::vector<Eigen::Isometry3d> bones_;
};

// The blinding test through every phase: people at several places of their schedule, each
// cube, both strategies' setups; on the grasp proxy, on worlds that force a slow close, a
// re-grasp, a lost cube and a trial cut by its time limit, on a world whose cube is caught on
// the hand (the wipe), and on the soft hand. The participant built from the other strategy's
// setup (seen_trial_of gives the same SeenTrial), with the same memory, fed what the first saw,
// sends the same frames bit for bit, ends with the same experience and memory, and its
// questionnaire answers are the same. Every phase of the state machine is gone through.
TEST(SimulatedParticipantBlinding, EveryPhaseSwappedConditionsSameFramesMemoryAndAnswers) {
  const Protocol protocol = read_protocol(kSource + "/studies/fine-manipulation-2021.json");
  PipelineTrialDriver driver(simulated_tracker(5));
  const QuestionnaireResponder answer = simulated_responder(5);
  std::set<std::string> phases;
  int runs = 0;
  auto same_seen = [](const SeenTrial& a, const SeenTrial& b) {
    return a.position == b.position && a.rate_hz == b.rate_hz &&
           a.hand.bone_length == b.hand.bone_length && a.hand.bone_radius == b.hand.bone_radius &&
           a.hand.thumb_distal == b.hand.thumb_distal && a.hand.index_distal == b.hand.index_distal;
  };
  enum class World { kProxy, kHideContact, kDropOnce, kCaught, kSoft };
  for (int who : {1, 6}) {
    const SimulatedPerson person = draw_person(Population{}, 5, who);
    const OwnHand own(person.participant.hand_length);
    const retarget::Calibration calibration = driver.calibrate(protocol, person.participant);
    ParticipantMemory memory;  // grows over this person's runs
    for (World world_kind :
         {World::kProxy, World::kHideContact, World::kDropOnce, World::kCaught, World::kSoft}) {
      for (double cube : {0.06, 0.01}) {
        if (world_kind == World::kSoft && (who != 1 || cube != 0.01)) continue;  // one, slow
        const std::vector<TrialSetup> setups =
            setups_of_cube(protocol, person, cube, 3 + 5 * runs % 19, calibration);
        ASSERT_EQ(setups.size(), 2u);
        ASSERT_NE(setups[0].condition.label, setups[1].condition.label);
        ASSERT_NE(setups[0].condition.strategy.method, setups[1].condition.strategy.method);
        ASSERT_TRUE(same_seen(seen_trial_of(setups[0], 120.0), seen_trial_of(setups[1], 120.0)));
        const hand::Skeleton sim = hand::build_simulated_hand(setups[0].condition.simulated_hand);
        task::SceneLayout layout = protocol.scene;
        layout.cube_size = cube;
        std::unique_ptr<task::HandCubeWorld> world;
        std::optional<hand::HandFlesh> flesh;
        std::optional<sim::HandSimModel> model;
        double limit = 30.0, rest_time = 0.5;
        switch (world_kind) {
          case World::kProxy: {
            task::GraspProxySettings g;
            g.cube_size = cube;
            world = std::make_unique<task::GraspProxyWorld>(
                sim, g, task::cube_start_pose(layout).translation());
            rest_time = 3.0;  // a task that waits longer for the cube to rest: it withdraws, idles
            break;
          }
          case World::kHideContact:
            world = std::make_unique<SeenOtherwiseWorld>(sim, layout,
                                                         SeenOtherwiseWorld::Twist::kHideContact);
            break;
          case World::kDropOnce:
            world = std::make_unique<SeenOtherwiseWorld>(sim, layout,
                                                         SeenOtherwiseWorld::Twist::kDropOnce);
            limit = 12.0;  // cut by its time limit
            break;
          case World::kCaught:
            world = std::make_unique<CaughtCubeWorld>(sim, layout);
            limit = 20.0;
            break;
          case World::kSoft: {
            flesh = hand::build_flesh(sim, setups[0].condition.simulated_hand);
            sim::SimParameters parameters;
            parameters.cube_size = cube;
            model = sim::make_hand_sim_model(sim, *flesh, parameters);
            world = std::make_unique<task::SoftHandWorld>(
                *model, sim, task::cube_start_pose(layout).translation(), sim::SimOptions{});
            limit = 5.0;
            break;
          }
        }
        auto first = participant_for(setups[0], 5, own, memory);
        auto second = participant_for(setups[1], 5, own, memory);
        const retarget::Strategy strategy = setups[0].condition.strategy.method;
        const ClosedLoop loop =
            drive(*first, *world, setups[0], strategy, limit, &phases, rest_time);
        for (std::size_t k = 0; k < loop.sent.size(); ++k)
          ASSERT_EQ(second->act(loop.shown[k]).hands.at(0).joints, loop.sent[k].hands.at(0).joints)
              << person.participant.id << " world " << int(world_kind) << " cube " << cube
              << " frame " << k;
        EXPECT_EQ(memory_to_json(second->memory_after()), memory_to_json(first->memory_after()));
        EXPECT_EQ(second->experience().time.seconds, first->experience().time.seconds);
        EXPECT_EQ(second->experience().time.missed_closings,
                  first->experience().time.missed_closings);
        EXPECT_EQ(second->experience().time.slips, first->experience().time.slips);
        TrialRun a, b;
        a.experience = first->experience();
        b.experience = second->experience();
        a.success = b.success = loop.success;
        a.completion_time_s = b.completion_time_s = double(loop.sent.size()) / 120.0;
        const SeenQuestionnaire asked{person.participant.id,
                                      setups[0].planned.position,
                                      limit,
                                      {"precision", "ease", "naturalness"},
                                      5};
        EXPECT_EQ(answer(asked, a), answer(asked, b));
        memory = first->memory_after();
        ++runs;
      }
    }
  }
  const std::set<std::string> all = {
      "react",     "reach",           "check reach", "descend", "check descent",
      "close",     "slow close",      "confirm",     "lift",    "check lift",
      "transport", "check transport", "lower",       "release", "wait rest",
      "withdraw",  "reopen",          "free cube",   "idle"};
  for (const std::string& phase : all) EXPECT_TRUE(phases.count(phase)) << "never in " << phase;
  EXPECT_EQ(runs, 17);
}

// What a slip teaches follows what the participant saw: a cube that dropped from the lifted
// pads while they stayed apart is gripped 3 mm harder on the next grasp, and one the pads
// closed over is grasped lower (and that is what the trial teaches its memory); a closing that
// ended without contact is tried again with the same grip. Its account of where the time went
// holds every frame it sent, and names each re-grasp's cause.
TEST(SimulatedParticipantGrip, ASlipGripsHarderOrLowerAsSeenNotAMissedClosing) {
  const StudyPerson p(2);
  const TrialSetup setup = setups_of_cube(p.protocol, p.person, 0.06, 4, p.calibration)[0];
  const hand::Skeleton sim = hand::build_simulated_hand(setup.condition.simulated_hand);
  task::SceneLayout layout = p.protocol.scene;
  layout.cube_size = 0.06;
  const retarget::Strategy strategy = setup.condition.strategy.method;
  {
    SeenOtherwiseWorld dropped(sim, layout, SeenOtherwiseWorld::Twist::kDropOnce);
    auto participant = participant_for(setup, 5, p.own, {});
    const ClosedLoop loop = drive(*participant, dropped, setup, strategy, 12.0);
    const TrialExperience e = participant->experience();
    ASSERT_GE(e.losses, 1);
    // The cube gone from between them, the pads closed where it was: they slid over it, and it
    // grasps lower (by one step at most), gripping no harder.
    EXPECT_EQ(e.slips, e.losses);
    EXPECT_DOUBLE_EQ(e.lowered, p.person.motor.regrasp_lower);
    EXPECT_EQ(e.squeeze_added, 0.0);
    EXPECT_EQ(e.time.trials, 1);
    EXPECT_NEAR(e.time.total(), double(loop.sent.size()) / 120.0, 1e-9);
    EXPECT_EQ(e.time.slips, e.losses);
    // Every closing but the last ended in a slip or, with the dropped cube's contact hidden
    // for good, a closing that saw none.
    EXPECT_GE(e.time.slips + e.time.missed_closings, e.grasp_attempts - 1);
    EXPECT_LE(e.time.slips + e.time.missed_closings, e.grasp_attempts);
    for (Activity a : {Activity::kReact, Activity::kReach, Activity::kDescend, Activity::kClose,
                       Activity::kLift, Activity::kReopen})
      EXPECT_GT(e.time[a], 0.0) << activity_name(a);
    EXPECT_EQ(e.time[Activity::kFreeCube], 0.0);
    EXPECT_DOUBLE_EQ(participant->memory_after().cube(0.06)->grasp_lower, e.lowered);
    // Each failed grasp gave back practice's speed-up of the grasp (post-error slowing).
    EXPECT_DOUBLE_EQ(e.caution_added,
                     (e.time.slips + e.time.missed_closings) * p.person.motor.post_error_caution);
    EXPECT_GT(participant->memory_after().cube(0.06)->caution.correction(), 0.0);
  }
  {
    SeenOtherwiseWorld apart(sim, layout, SeenOtherwiseWorld::Twist::kDropPadsApart);
    auto participant = participant_for(setup, 5, p.own, {});
    drive(*participant, apart, setup, strategy, 12.0);
    const TrialExperience e = participant->experience();
    ASSERT_GE(e.slips, 1);
    EXPECT_NEAR(e.squeeze_added, e.slips * p.person.motor.regrasp_squeeze, 1e-12);
    EXPECT_EQ(e.lowered, 0.0);
    EXPECT_DOUBLE_EQ(participant->memory_after().cube(0.06)->grip_margin, e.squeeze_added);
    EXPECT_EQ(participant->memory_after().cube(0.06)->grasp_lower, 0.0);
  }
  {
    // The small cube: the slow closing shuts the hand before the hidden contact shows.
    const TrialSetup fine = setups_of_cube(p.protocol, p.person, 0.01, 4, p.calibration)[0];
    layout.cube_size = 0.01;
    SeenOtherwiseWorld hidden(sim, layout, SeenOtherwiseWorld::Twist::kHideContact);
    auto participant = participant_for(fine, 5, p.own, {});
    const ClosedLoop loop = drive(*participant, hidden, fine, fine.condition.strategy.method, 30.0);
    const TrialExperience e = participant->experience();
    ASSERT_GE(e.grasp_attempts, 2);  // the closing missed, and it closed again
    EXPECT_EQ(e.losses, 0);
    EXPECT_NEAR(e.time.total(), double(loop.sent.size()) / 120.0, 1e-9);
    EXPECT_EQ(e.time.missed_closings, e.grasp_attempts - 1);
    EXPECT_EQ(e.time.slips, 0);
    EXPECT_GT(e.time[Activity::kReopen], 0.0);
    EXPECT_GT(e.time[Activity::kSetDown], 0.0);  // then it carried the cube to B
    EXPECT_EQ(e.squeeze_added, 0.0);
    EXPECT_EQ(e.lowered, 0.0);
    EXPECT_EQ(participant->memory_after().cube(0.01)->grip_margin, 0.0);
    // A missed closing is a failed grasp all the same: it slows the grasps after it.
    EXPECT_DOUBLE_EQ(e.caution_added, e.time.missed_closings * p.person.motor.post_error_caution);
  }
}

// The memory of a person six trials in, three of them with this cube, who has learnt nothing
// of its grip or its pads' height.
ParticipantMemory having_handled(double cube) {
  ParticipantMemory memory;
  memory.trials = 6;
  CubeMemory remembered;
  remembered.cube_size = cube;
  remembered.trials = 3;
  memory.cubes.push_back(remembered);
  return memory;
}

// A person whose pads slid over the cube grasps it lower by the step it learnt (the memory's
// grasp_lower, kept from trial to trial): its hand goes lower to pick it up, with either cube,
// and the trial still succeeds.
TEST(SimulatedParticipantGrip, PadsThatSlidOverTheCubeAreSetLowerNextTime) {
  const StudyPerson p(2);
  for (const double cube : {0.01, 0.06}) {
    const TrialSetup setup = setups_of_cube(p.protocol, p.person, cube, 6, p.calibration)[0];
    const ParticipantMemory plain = having_handled(cube);
    ParticipantMemory lowered = plain;
    const double step = p.person.motor.regrasp_lower;
    lowered.cubes[0].grasp_lower = step;
    auto without = participant_for(setup, 5, p.own, plain);
    auto with = participant_for(setup, 5, p.own, lowered);
    const ClosedLoop a = run_closed_loop(*without, setup);
    const ClosedLoop b = run_closed_loop(*with, setup);
    ASSERT_TRUE(a.success && b.success) << cube;
    // Where its own grip is as it closes on the cube: the lowest until a quarter second after
    // both pads are first shown on it (before the lift).
    auto lowest = [](const ClosedLoop& loop) {
      std::size_t both_seen = 0;
      while (both_seen < loop.shown.size() &&
             !(loop.shown[both_seen].thumb_touching && loop.shown[both_seen].index_touching))
        ++both_seen;
      double y = INFINITY;
      for (std::size_t i = 0; i < std::min(both_seen + 30, loop.own_grip.size()); ++i)
        y = std::min(y, loop.own_grip[i].y());
      return y;
    };
    // The seen pads are set a step lower; the own hand follows through the mapping and the
    // descent's corrections (4.4 and 5.3 mm with this person).
    EXPECT_LT(lowest(b), lowest(a) - 0.5 * step) << cube;
    EXPECT_GT(lowest(b), lowest(a) - 3.0 * step) << cube;
    // Never more than one step: a memory of two moves the hand exactly as one of one.
    ParticipantMemory twice = plain;
    twice.cubes[0].grasp_lower = 2 * step;
    auto bounded = participant_for(setup, 5, p.own, twice);
    EXPECT_EQ(run_closed_loop(*bounded, setup).own_grip, b.own_grip) << cube;
  }
}

// The grip a slip taught is added once the pads touch, in the loading phase (grip force builds
// up after contact: Johansson & Westling 1984), not to where the closing aims: a person with
// a margin (6 mm, bounded to half the side, 5 mm, on the 1 cm cube) moves exactly as one
// without until it has seen both pads on the cube, then closes further before it lifts; a
// remembered margin past the bound moves the hand exactly as the bound.
TEST(SimulatedParticipantGrip, TheGripMarginIsAddedAfterContactNotToTheClosingsAim) {
  const StudyPerson p(2);
  for (const double cube : {0.01, 0.06}) {
    const TrialSetup setup = setups_of_cube(p.protocol, p.person, cube, 6, p.calibration)[0];
    const ParticipantMemory plain = having_handled(cube);
    ParticipantMemory gripping = plain;
    const double margin = 0.006;
    gripping.cubes[0].grip_margin = margin;
    auto without = participant_for(setup, 5, p.own, plain);
    auto with = participant_for(setup, 5, p.own, gripping);
    const ClosedLoop a = run_closed_loop(*without, setup);
    const ClosedLoop b = run_closed_loop(*with, setup);
    ASSERT_TRUE(a.success && b.success) << cube;
    std::size_t both_seen = 0;
    while (both_seen < a.shown.size() &&
           !(a.shown[both_seen].thumb_touching && a.shown[both_seen].index_touching))
      ++both_seen;
    std::size_t apart = 0;
    while (apart < std::min(a.own_aperture.size(), b.own_aperture.size()) &&
           a.own_aperture[apart] == b.own_aperture[apart])
      ++apart;
    EXPECT_GT(apart, both_seen) << cube << ": the margin moved the closing before contact";
    // ... and as it starts loading, one visual delay after the contact was shown (the lift
    // comes a confirmation dwell later).
    const auto seen_then = std::size_t(std::ceil(p.person.motor.visual_delay * 120.0));
    EXPECT_LE(apart, both_seen + seen_then + 2) << cube;
    const double a_min = *std::min_element(a.own_aperture.begin(), a.own_aperture.end());
    const double b_min = *std::min_element(b.own_aperture.begin(), b.own_aperture.end());
    EXPECT_LT(b_min, a_min - 0.5 * margin) << cube;
    ParticipantMemory at_bound = plain, past_bound = plain;
    at_bound.cubes[0].grip_margin = 0.5 * cube;
    past_bound.cubes[0].grip_margin = 4 * cube;
    auto bounded = participant_for(setup, 5, p.own, at_bound);
    auto past = participant_for(setup, 5, p.own, past_bound);
    EXPECT_EQ(run_closed_loop(*past, setup).own_aperture,
              run_closed_loop(*bounded, setup).own_aperture)
        << cube;
  }
}

// Where a pad first meets the cube is learnt closing by closing, each closing a movement of the
// two-state model: the closings after one whose pad met the cube sooner than expected end
// sooner, so that the pads arrive as the closing slows down (Smeets & Brenner 1999).
TEST(SimulatedParticipantGrip, EachClosingLearnsWhereAPadFirstMeetsTheCube) {
  const StudyPerson p(2);
  ParticipantMemory memory;
  TwoRateState expected;
  std::vector<double> first_errors;
  for (int position = 0; position < 6; ++position) {
    const TrialSetup setup = setups_of_cube(p.protocol, p.person, 0.01, position, p.calibration)[0];
    auto participant = participant_for(setup, 5, p.own, memory);
    ASSERT_TRUE(run_closed_loop(*participant, setup).success);
    const TrialExperience& e = participant->experience();
    ASSERT_EQ(e.contact_errors.size(), std::size_t(e.grasp_attempts));
    ASSERT_TRUE(e.contact_errors.front().has_value());
    first_errors.push_back(*e.contact_errors.front());
    for (const std::optional<double>& error : e.contact_errors)
      expected = after_closing(expected, error, p.person.motor.contact_rates);
    memory = participant->memory_after();
    EXPECT_DOUBLE_EQ(memory.cube(0.01)->contact.correction(), expected.correction());
  }
  // The pads met the unpractised cube sooner (6.8 mm); six trials later the error is down
  // to 3.9 mm, where the fast state's forgetting balances its learning and the slow state
  // has only begun (a constant error e gives the fast state 0.21 e / 0.41).
  EXPECT_GT(first_errors.front(), 0.0);
  EXPECT_LT(std::abs(first_errors.back()), 0.7 * first_errors.front());
}

// Where its pads end up against the cube is learnt closing by closing too (an offset of the
// visuomotor map of grasping, Safstrom & Edin 2005): the memory holds the two-state fold of the
// aim errors its closings saw, and a person who remembers its pads ending up 4 mm along x (or
// z) aims them 4 mm short of that, so that they meet the cube 2 to 6 mm further back.
TEST(SimulatedParticipantGrip, EachClosingLearnsWhereItsPadsEndUpAgainstTheCube) {
  const StudyPerson p(2);
  ParticipantMemory memory;
  TwoRateState x, z;
  for (int position = 0; position < 4; ++position) {
    const TrialSetup setup = setups_of_cube(p.protocol, p.person, 0.01, position, p.calibration)[0];
    auto participant = participant_for(setup, 5, p.own, memory);
    ASSERT_TRUE(run_closed_loop(*participant, setup).success);
    const TrialExperience& e = participant->experience();
    ASSERT_FALSE(e.aim_errors.empty());
    for (const std::array<double, 2>& error : e.aim_errors) {
      x = adapt(x, p.person.motor.contact_rates, error[0]);
      z = adapt(z, p.person.motor.contact_rates, error[1]);
    }
    memory = participant->memory_after();
    EXPECT_DOUBLE_EQ(memory.cube(0.01)->aim_x.correction(), x.correction());
    EXPECT_DOUBLE_EQ(memory.cube(0.01)->aim_z.correction(), z.correction());
  }
  // A remembered shift along x, then along z: the pads meet the cube that much further back
  // on that axis, give or take what the servo (3 /s) makes of the new aim before contact.
  const double shift = 0.004;
  for (const double cube : {0.01, 0.06})
    for (const int axis : {0, 1}) {
      const TrialSetup setup = setups_of_cube(p.protocol, p.person, cube, 5, p.calibration)[0];
      const ParticipantMemory plain = memory_of_cube(cube, 3);
      ParticipantMemory shifted = plain;
      (axis == 0 ? shifted.cubes[0].aim_x : shifted.cubes[0].aim_z).fast = shift;
      auto as_before = participant_for(setup, 5, p.own, plain);
      auto aiming_back = participant_for(setup, 5, p.own, shifted);
      ASSERT_TRUE(run_closed_loop(*as_before, setup).success) << cube;
      ASSERT_TRUE(run_closed_loop(*aiming_back, setup).success) << cube;
      // Both first errors are of the first closing (a pad touched in it).
      ASSERT_TRUE(as_before->experience().contact_errors.front().has_value()) << cube;
      ASSERT_TRUE(aiming_back->experience().contact_errors.front().has_value()) << cube;
      const double before = as_before->experience().aim_errors.front()[std::size_t(axis)];
      const double after = aiming_back->experience().aim_errors.front()[std::size_t(axis)];
      EXPECT_LT(after - before, -0.5 * shift) << cube << " axis " << axis;
      EXPECT_GT(after - before, -1.5 * shift) << cube << " axis " << axis;
    }
}

// The aim learnt at a closing's first touch steers the rest of that closing. The same
// observations replayed with the cube seen 3 mm further along x from the one in which it saw
// the touch: the aim error it takes in is 3 mm smaller, and the servo carries its own grip
// after the cube by 3 mm plus (B_fast + B_slow) 3 mm of adapted aim; moved from the next
// observation on, by the 3 mm alone.
TEST(SimulatedParticipantGrip, TheAimLearntAtATouchSteersTheRestOfThatClosing) {
  const StudyPerson p(2);
  const TrialSetup setup = setups_of_cube(p.protocol, p.person, 0.01, 3, p.calibration)[0];
  auto original = participant_for(setup, 5, p.own);
  const ClosedLoop loop = run_closed_loop(*original, setup);
  ASSERT_TRUE(loop.success);
  const std::array<double, 2> seen_error = original->experience().aim_errors.at(0);
  const double shift = 0.003;
  struct Replay {
    std::vector<Eigen::Vector3d> grip;
    std::vector<std::string> phase;
    std::array<double, 2> first_error{};
  };
  auto replay = [&](std::size_t from) {
    auto participant = participant_for(setup, 5, p.own);
    Replay r;
    for (std::size_t k = 0; k + 1 < loop.shown.size(); ++k) {
      Observation o = loop.shown[k];
      if (k >= from) o.cube_position.x() += shift;
      participant->act(o);
      r.grip.push_back(participant->own_grip());
      r.phase.push_back(participant->phase_name());
    }
    r.first_error = participant->experience().aim_errors.at(0);
    return r;
  };
  // The observation it took the touch from: the first with a pad on the cube, or a later one
  // if that came before its closing; the last from which a shift changes the first aim error.
  std::size_t touch = loop.shown.size();
  for (std::size_t k = 0; k < loop.shown.size() && touch == loop.shown.size(); ++k)
    if (loop.shown[k].thumb_touching || loop.shown[k].index_touching) touch = k;
  ASSERT_LT(touch, loop.shown.size());
  while (replay(touch + 1).first_error[0] != seen_error[0]) ++touch;
  const Replay moved = replay(touch), after = replay(touch + 1);
  EXPECT_NEAR(moved.first_error[0], seen_error[0] - shift, 1e-12);
  EXPECT_EQ(after.first_error[0], seen_error[0]);
  // Up to the end of the loading's dwell, where the servo stops.
  std::size_t end = touch;
  while (end < moved.phase.size() && (moved.phase[end] == std::string("close") ||
                                      moved.phase[end] == std::string("slow close") ||
                                      moved.phase[end] == std::string("confirm")))
    ++end;
  ASSERT_GT(end, touch + 20);
  const double followed_moved = moved.grip[end - 1].x() - loop.own_grip[end - 1].x();
  const double followed_after = after.grip[end - 1].x() - loop.own_grip[end - 1].x();
  const TwoRateRates& r = p.person.motor.contact_rates;
  EXPECT_GT(followed_after, 0.0);
  EXPECT_NEAR(followed_moved / followed_after - 1.0, r.learn_fast + r.learn_slow, 0.07);
}

// A practised grasp is fast; a person who has just failed grasps gives that speed back
// (post-error slowing), and only the grasp: the reach is as practised as before.
TEST(SimulatedParticipantGrip, CautionAfterFailuresSlowsTheGraspNotTheReach) {
  const StudyPerson p(2);
  const TrialSetup setup = setups_of_cube(p.protocol, p.person, 0.06, 9, p.calibration)[0];
  const ParticipantMemory practised = memory_of_cube(0.06, 8);
  ParticipantMemory cautious = practised;
  cautious.cubes[0].caution.fast = 1.0;
  auto quick = participant_for(setup, 5, p.own, practised);
  auto careful = participant_for(setup, 5, p.own, cautious);
  ASSERT_TRUE(run_closed_loop(*quick, setup).success);
  ASSERT_TRUE(run_closed_loop(*careful, setup).success);
  const ActivityTime& q = quick->experience().time;
  const ActivityTime& c = careful->experience().time;
  EXPECT_DOUBLE_EQ(c[Activity::kReach], q[Activity::kReach]);
  // The closing, loading and dwell at the unpractised pace: practice had taken 1 - f(9) of it.
  const double f = practice_factor(9, p.person.motor.practice_rate, p.person.motor.practice_floor);
  EXPECT_GT(c[Activity::kClose],
            q[Activity::kClose] +
                0.5 * (1 - f) * (p.person.motor.closing_time + p.person.motor.confirm_dwell));
  EXPECT_GT(c[Activity::kLift], q[Activity::kLift]);
  EXPECT_EQ(careful->memory_after().cube(0.06)->caution.correction(),
            adapt({1.0, 0.0}, p.person.motor.contact_rates, 0.0).correction());
}

// A cube stuck to the virtual thumb does not make it chase the cube upwards (each reach for
// a cube it carries lifts the cube with it): it opens the hand, then wipes the cube off on the
// floor, and reaches for it where it fell.
TEST(SimulatedParticipantCare, WipesOffACubeCaughtOnItsThumb) {
  const Protocol protocol = read_protocol(kSource + "/studies/fine-manipulation-2021.json");
  PipelineTrialDriver driver(simulated_tracker(5));
  const SimulatedPerson person = draw_person(Population{}, 5, 3);
  const OwnHand own(person.participant.hand_length);
  TrialSetup setup;
  setup.protocol = &protocol;
  setup.participant = person.participant;
  setup.planned.position = 7;
  setup.calibration = driver.calibrate(protocol, person.participant);
  // The 1 cm cube's two conditions: the participant of the second, fed what the first saw,
  // must send the same frames (blinding, through the behaviours this world provokes).
  std::vector<Condition> fine;
  for (const Condition& c : protocol.conditions())
    if (c.cube_size == 0.01) fine.push_back(c);
  ASSERT_EQ(fine.size(), 2u);
  ASSERT_NE(fine[0].strategy.method, fine[1].strategy.method);
  setup.condition = fine[0];
  TrialSetup swapped = setup;
  swapped.condition = fine[1];
  const hand::Skeleton sim = hand::build_simulated_hand(setup.condition.simulated_hand);
  task::SceneLayout layout = protocol.scene;
  layout.cube_size = 0.01;
  CaughtCubeWorld world(sim, layout);
  retarget::Retargeter retargeter(retarget::Strategy::kOurs, sim, setup.calibration);
  auto participant = participant_for(setup, 5, own);
  auto blind = participant_for(swapped, 5, own);
  Observation shown = display_observation(world, layout, 0.0);
  bool same_frames = true;
  double freed_at = -1.0, nearest_after = INFINITY;
  Eigen::Vector3d resting = Eigen::Vector3d::Zero();
  for (long step = 1; step <= 120 * 40; ++step) {
    const double t = double(step) / 120.0;
    const tracking::TrackedFrame sent = participant->act(shown);
    same_frames = same_frames && blind->act(shown).hands.at(0).joints == sent.hands.at(0).joints;
    const hand::HandPose pose = retargeter.retarget(sent.hands.at(0)).pose;
    world.step(&pose, 1.0 / 120.0);
    shown = display_observation(world, layout, t);
    if (freed_at < 0 && world.freed()) {
      freed_at = t;
      resting = world.cube().position;
    }
    if (freed_at >= 0 && !shown.bones.empty()) {
      const Eigen::Isometry3d& tip = shown.bones[std::size_t(sim.bone_index("index3"))];
      nearest_after = std::min(nearest_after, (tip.translation() - resting).norm());
    }
  }
  std::cout << "caught cube: freed at " << freed_at << " s, highest " << world.highest_caught()
            << " m, index tip within " << nearest_after << " m of it after, "
            << participant->experience().corrections << " corrections\n";
  ASSERT_GE(freed_at, 0.0) << "it never took the caught cube down to the floor";
  EXPECT_LT(world.highest_caught(), 0.15) << "it chased the cube it carried upwards";
  EXPECT_LT(nearest_after, 0.05) << "it did not reach for the cube where it fell";
  EXPECT_GE(participant->experience().corrections, 2);  // opening wide, wiping
  EXPECT_TRUE(same_frames) << "the other strategy's label changed what it sent";
  EXPECT_EQ(blind->experience().corrections, participant->experience().corrections);
}

// Its own hand: the tracked skeleton at its size, the pads the asked aperture apart.
TEST(OwnHand, PinchPosturesSpanTheApertures) {
  const OwnHand own(0.188);
  for (Pinch pinch : {Pinch::kPad, Pinch::kTip}) {
    EXPECT_LT(own.min_aperture(pinch), 0.01);
    EXPECT_GT(own.max_aperture(pinch), 0.09);
    const Eigen::Vector3d grip(0.1, 0.05, 0.0);
    const hand::HandPose a = own.pose(pinch, grip, 0.02), b = own.pose(pinch, grip, 0.06);
    const tracking::TrackedFrame fa = own.frame(a, 0.0, 1, {}), fb = own.frame(b, 0.0, 2, {});
    const auto& ja = fa.hands.at(0).joints;
    const auto& jb = fb.hands.at(0).joints;
    EXPECT_LT((ja[0][4] - ja[1][4]).norm(), (jb[0][4] - jb[1][4]).norm());
    // Middle, ring and little fingers open with the pinch (a postural synergy): less flexed
    // at every joint with the pads 9 cm apart than 1 cm apart, curled out of the way when
    // closed.
    const hand::HandPose closed = own.pose(pinch, grip, 0.01), open = own.pose(pinch, grip, 0.09);
    int others = 0;
    for (std::size_t k = 0; k < own.skeleton().dofs.size(); ++k) {
      const hand::Dof& dof = own.skeleton().dofs[k];
      const bool other = dof.name.rfind("middle", 0) == 0 || dof.name.rfind("ring", 0) == 0 ||
                         dof.name.rfind("pinky", 0) == 0;
      if (!other || dof.name.find("flexion") == std::string::npos) continue;
      ++others;
      const Eigen::Index i = Eigen::Index(k);
      EXPECT_LT(open.angles(i), closed.angles(i) - 0.3 * dof.upper) << dof.name;
      EXPECT_GT(closed.angles(i), 0.6 * dof.upper) << dof.name;
    }
    EXPECT_GE(others, 6);
  }
}

}  // namespace
}  // namespace handlab::studies
