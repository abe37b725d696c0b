#include "studies/simulate/simulated_study.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <thread>
#include <vector>

#include "core/store/sqlite_database.h"
#include "core/store/study_store.h"
#include "core/util/temporary_files.h"
#include "studies/session/group_assignment.h"
#include "studies/session/session_runner.h"

namespace handlab::studies {
namespace {

std::string part_path(const std::string& db_path, const std::string& id) {
  return db_path + ".part-" + id;
}

}  // namespace

SimulationReport simulate_study(const Protocol& protocol, const std::string& db_path,
                                const SimulationOptions& options,
                                const std::function<void(const SimulationProgress&)>& progress) {
  if (options.participants < 1) throw std::invalid_argument("a study needs participants");
  std::vector<int> indices = options.only;
  if (indices.empty())
    for (int i = 0; i < options.participants; ++i) indices.push_back(i);
  std::sort(indices.begin(), indices.end());
  if (indices.front() < 0 || indices.back() >= options.participants ||
      std::adjacent_find(indices.begin(), indices.end()) != indices.end())
    throw std::invalid_argument("a shard's participants are distinct places in the study");
  if (std::filesystem::exists(db_path))
    throw std::runtime_error(db_path + " exists; a simulated study is written to a new file");
  const auto start = std::chrono::steady_clock::now();
  store::StudyDefinition definition = study_definition(protocol);
  definition.planned_participants = options.participants;

  // Everyone drawn and placed in their groups before the file exists: a person the protocol
  // has no group for stops the study before it starts.
  std::vector<SimulatedPerson> persons;
  for (int i : indices) {
    persons.push_back(draw_person(options.population, options.seed, i, options.model));
    store::Participant& p = persons.back().participant;
    try {
      p.between_levels = assign_groups(protocol, p, i);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("simulated participant " + p.id + " (population seed " +
                                  std::to_string(options.seed) + "): " + e.what());
    }
  }
  // A simulated study is whole or not there: it is built as DB.creating (which every command
  // that opens a study refuses, if a killed run left it) and renamed when complete; it and
  // its sessions' parts are removed if the run fails or is stopped (Ctrl-C, a batch system's
  // cancel).
  const std::string building = db_path + ".creating";
  util::TemporaryDatabase unfinished_study(building);
  store::remove_database_files(building);
  std::vector<std::unique_ptr<util::TemporaryDatabase>> unfinished_parts;
  // Enrolled in order: the schedules' counterbalancing follows enrolment.
  store::StudyStore::create(building, definition);
  std::optional<store::StudyStore> open_study;
  store::StudyStore& study = open_study.emplace(building, store::StudyStore::Access::kUnfinished);
  std::vector<store::Participant> people;
  std::vector<std::vector<store::PlannedTrialRow>> plans;
  int planned_total = 0;
  for (std::size_t k = 0; k < persons.size(); ++k) {
    const SimulatedPerson& person = persons[k];
    plans.push_back(planned_rows(protocol, person.participant.id, indices[k]));
    study.add_participant(person.participant, plans.back(), indices[k]);
    study.add_simulated_person(simulated_person_row(person, options.seed, options.model));
    people.push_back(person.participant);
    planned_total += int(plans.back().size());
  }

  // Sessions side by side, each in a copy of the enrolled study; imported in enrolment order.
  for (const store::Participant& p : people) {
    const std::string path = part_path(db_path, p.id);
    store::remove_database_files(path);
    unfinished_parts.push_back(std::make_unique<util::TemporaryDatabase>(path));
    study.copy_to(path);
  }
  const int n = int(people.size());
  const TrackerPtr tracker = simulated_tracker(options.seed, options.model);
  const std::string tracker_name =
      options.world == WorldKind::kSoftHand ? tracker->name() + " (soft hand)" : tracker->name();
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<int> state(std::size_t(n), 0);  // 0 waiting, 1 running, 2 done
  std::atomic<int> next{0};
  std::atomic<bool> stop{false};
  std::exception_ptr failure;
  int trials_done = 0;
  std::map<std::string, sim::StepTotals> simulator;  // per condition label
  // Per participant and cube seen, summed in enrolment order when all are done: the totals'
  // last digits do not depend on which session ended first.
  std::vector<std::map<double, ActivityTime>> participant_time(static_cast<std::size_t>(n));

  auto work = [&] {
    for (int i = next++; i < n && !stop; i = next++) {
      const std::string path = part_path(db_path, people[std::size_t(i)].id);
      try {
        store::StudyStore part(path);
        PipelineTrialDriver driver(tracker, 120.0, options.world, 1);
        SessionRunner runner(part, driver, *tracker->own_answers());
        runner.log_frames(options.frames);
        const SessionReport report =
            runner.run(people[std::size_t(i)].id, tracker_name, false, [&](const std::string&) {
              const std::lock_guard lock(mutex);
              ++trials_done;
              changed.notify_all();
            });
        const std::lock_guard lock(mutex);
        for (const auto& [label, t] : report.simulator) simulator[label] += t;
        participant_time[std::size_t(i)] = report.participant_time;
      } catch (...) {
        const std::lock_guard lock(mutex);
        if (!failure) failure = std::current_exception();
        stop = true;
      }
      const std::lock_guard lock(mutex);
      state[std::size_t(i)] = 2;
      changed.notify_all();
    }
  };
  const int jobs = std::clamp(options.jobs, 1, n);
  std::vector<std::thread> threads;
  for (int j = 0; j < jobs; ++j) threads.emplace_back(work);

  SimulationProgress shown{0, n, 0, planned_total, 0.0};
  int imported = 0;
  std::exception_ptr import_failure;
  {
    std::unique_lock lock(mutex);
    while (imported < n && !failure) {
      changed.wait_for(lock, std::chrono::milliseconds(500));
      shown.trials_done = trials_done;
      while (imported < n && state[std::size_t(imported)] == 2 && !failure) {
        const std::string path = part_path(db_path, people[std::size_t(imported)].id);
        lock.unlock();
        try {
          study.import_sessions(path);
          store::remove_database_files(path);
        } catch (...) {
          import_failure = std::current_exception();
        }
        lock.lock();
        if (import_failure) {
          failure = import_failure;
          stop = true;
          break;
        }
        ++imported;
      }
      shown.participants_done = imported;
      shown.seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (progress) {
        lock.unlock();
        progress(shown);
        lock.lock();
      }
    }
  }
  for (std::thread& t : threads) t.join();
  if (failure) {
    for (const store::Participant& p : people)
      store::remove_database_files(part_path(db_path, p.id));
    std::rethrow_exception(failure);
  }

  SimulationReport report;
  report.participants = n;
  report.conditions = condition_outcomes(study, protocol);
  for (const Condition& c : protocol.conditions())
    report.simulator.emplace_back(c.label, simulator[c.label]);
  std::map<double, ActivityTime> by_cube;
  for (const auto& person : participant_time)
    for (const auto& [cube, t] : person) by_cube[cube] += t;
  report.participant_time.assign(by_cube.begin(), by_cube.end());
  for (const store::Participant& p : people)
    for (const store::TrialRow& t : study.trials(p.id)) {
      ++report.trials;
      if (t.status == store::TrialStatus::kCompleted) {
        ++report.completed;
        report.simulated_seconds += t.completion_time_s;
      } else if (t.status == store::TrialStatus::kTimeout) {
        ++report.timeouts;
        report.simulated_seconds += protocol.timeout_s;
      }
    }
  open_study.reset();  // closed: its log checkpointed into the file
  if (std::filesystem::exists(db_path))
    throw std::runtime_error(db_path + " appeared while the study ran; it is left as it is");
  std::filesystem::rename(building, db_path);
  unfinished_study.keep();  // the study, now whole under its name
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

}  // namespace handlab::studies
