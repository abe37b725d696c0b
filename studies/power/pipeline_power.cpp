#include "studies/power/pipeline_power.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "studies/analysis/study_database_analysis.h"
#include "studies/analysis/study_tests.h"
#include "studies/cluster/slurm_batch.h"
#include "studies/simulate/simulated_study.h"

namespace handlab::studies {
namespace {

struct Outcome {
  std::vector<std::pair<std::string, bool>> effects, contrasts;
  std::string warning;
};

// What one simulated study's analysis rejects: as `power` judges a model's studies. Its
// tests are named as study_tests names them, pairs of cells in the protocol's order.
Outcome outcome_of(const StudyDatabaseAnalysis& a, const power::PowerOptions& o) {
  const StudyTests found = study_tests(a, o.correction, o.alpha);
  Outcome out;
  for (const StudyTest& t : found.tests)
    (t.contrast ? out.contrasts : out.effects).emplace_back(t.name, t.p < o.alpha);
  out.warning = found.warning;
  return out;
}

void remove_study(const std::filesystem::path& db) {
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
    std::error_code ignored;
    std::filesystem::remove(db.string() + suffix, ignored);
  }
}

}  // namespace

std::vector<std::vector<PipelineStudy>> pipeline_studies(const power::PowerOptions& o) {
  std::vector<std::vector<PipelineStudy>> studies(o.n.size());
  for (std::size_t k = 0; k < o.n.size(); ++k)
    for (int s = 0; s < o.sims; ++s)
      studies[k].push_back(
          {o.n[k], util::splitmix64(o.seed ^ util::splitmix64(std::uint64_t(o.n[k]) * 1000003ull +
                                                              std::uint64_t(s)))});
  return studies;
}

power::PowerReport pipeline_power(const Protocol& protocol, const PipelinePowerOptions& options,
                                  const std::function<void(int, int)>& progress) {
  const power::PowerOptions& o = options.power;
  if (o.n.empty()) throw std::invalid_argument("no N to compute the power for");
  if (o.sims < 1) throw std::invalid_argument("sims must be 1 or more");
  const std::filesystem::path dir = options.work_dir.empty()
                                        ? std::filesystem::temp_directory_path()
                                        : std::filesystem::path(options.work_dir);
  std::filesystem::create_directories(dir);
  // Every study's outcome first: the report names every test any study computed (a study
  // whose ANOVA could not be computed names none of its effects).
  std::vector<std::vector<Outcome>> outcomes(o.n.size());
  std::vector<double> seconds(o.n.size(), 0.0);
  const int total = int(o.n.size()) * o.sims;
  int done = 0;
  const std::vector<std::vector<PipelineStudy>> planned = pipeline_studies(o);
  for (std::size_t k = 0; k < o.n.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < o.sims; ++s) {
      const PipelineStudy& study = planned[k][std::size_t(s)];
      if (!options.from_dir.empty()) {
        const std::string db = study_path(options.from_dir, {study.participants, study.seed});
        if (!std::filesystem::exists(db))
          throw std::runtime_error(db +
                                   " is missing: the series is unfinished (simulate --status " +
                                   options.from_dir + ")");
        outcomes[k].push_back(outcome_of(analyze_study_database(db), o));
        if (progress) progress(++done, total);
        continue;
      }
      const std::filesystem::path db =
          dir / ("handlab-power-" + std::to_string(o.n[k]) + "-" + std::to_string(s) + "-" +
                 std::to_string(util::splitmix64(o.seed) % 100000) + ".db");
      remove_study(db);
      SimulationOptions so;
      so.participants = study.participants;
      so.seed = study.seed;
      so.jobs = std::max(1, o.threads);
      so.world = options.world;
      try {
        simulate_study(protocol, db.string(), so);
        outcomes[k].push_back(outcome_of(analyze_study_database(db.string()), o));
      } catch (...) {
        remove_study(db);
        throw;
      }
      remove_study(db);
      if (progress) progress(++done, total);
    }
    seconds[k] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  std::vector<std::string> effects, contrasts;
  auto add = [](std::vector<std::string>& names, const std::string& name) {
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  };
  for (const auto& per_n : outcomes)
    for (const Outcome& out : per_n) {
      for (const auto& [name, _] : out.effects) add(effects, name);
      for (const auto& [name, _] : out.contrasts) add(contrasts, name);
    }
  power::PowerReport report = power::empty_report(effects, contrasts, o.n, o.sims, o.alpha);
  std::vector<std::string> examples;
  for (std::size_t k = 0; k < o.n.size(); ++k) {
    std::vector<long> effect_hits(effects.size(), 0), contrast_hits(contrasts.size(), 0);
    int warnings = 0;
    for (Outcome out : outcomes[k]) {
      auto count = [&](const std::vector<std::string>& names, std::vector<long>& hits,
                       const std::vector<std::pair<std::string, bool>>& seen) {
        std::size_t found = 0;
        for (std::size_t i = 0; i < names.size(); ++i)
          for (const auto& [name, rejected] : seen)
            if (name == names[i]) {
              hits[i] += rejected;
              ++found;
              break;
            }
        return found == names.size();
      };
      const bool all =
          count(effects, effect_hits, out.effects) & count(contrasts, contrast_hits, out.contrasts);
      if (!all && out.warning.empty()) out.warning = "some tests were not computed";
      if (!out.warning.empty()) {
        ++warnings;
        if (examples.size() < 5)
          examples.push_back("N = " + std::to_string(o.n[k]) + ": " + out.warning);
      }
    }
    power::set_counts(report, k, effect_hits, contrast_hits, warnings, seconds[k]);
  }
  report.warning_examples = examples;
  report.notes.push_back(
      options.from_dir.empty()
          ? std::string("pipeline: whole simulated studies on the ") +
                (options.world == WorldKind::kSoftHand ? "soft hand" : "grasp proxy") +
                ", analysed by analyze --db"
          : "pipeline: whole simulated studies run as Slurm jobs, merged in " + options.from_dir +
                ", analysed by analyze --db");
  return report;
}

}  // namespace handlab::studies
