#include "studies/power/pipeline_power.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "studies/analysis/study_database_analysis.h"
#include "studies/simulate/simulated_study.h"

namespace handlab::studies {
namespace {

struct Outcome {
  std::vector<std::pair<std::string, bool>> effects, contrasts;
  std::string warning;
};

// What one simulated study's analysis rejects: as `power` judges a model's studies.
Outcome outcome_of(const StudyDatabaseAnalysis& a, const std::string& planned,
                   const power::PowerOptions& o) {
  Outcome out;
  if (!a.completion_time) {
    out.warning = "completion time not analysed: " + a.completion_time_not_computed;
  } else {
    const analysis::AnalysisReport& t = *a.completion_time;
    for (const stats::AnovaEffect& e : t.anova.effects)
      out.effects.emplace_back(e.effect, power::judged_p(e, o.correction, o.alpha) < o.alpha);
    for (const stats::PosthocResult& r : t.posthoc)
      for (const stats::PairwiseContrast& c : r.contrasts)
        if (c.effect == planned)
          out.contrasts.emplace_back(power::contrast_name(c), c.p_tukey < o.alpha);
    if (!t.dropped_subjects.empty())
      out.warning = std::to_string(t.dropped_subjects.size()) +
                    " participant(s) left out, lacking a result in some cell";
  }
  if (a.questionnaire) {
    for (const analysis::FriedmanItem& f : a.questionnaire->friedman)
      out.effects.emplace_back(f.dv + " (Friedman)", f.result.p < o.alpha);
    for (const analysis::WilcoxonPair& w : a.questionnaire->wilcoxon)
      out.contrasts.emplace_back(w.dv + ": " + w.contrast + " (Wilcoxon)",
                                 w.p_bonferroni < o.alpha);
  } else if (out.warning.empty() && !a.protocol.items.empty()) {
    out.warning = "questionnaire not analysed: " + a.questionnaire_not_computed;
  }
  return out;
}

// "a - b" and "b - a" name one two-sided test (levels are ordered as the data first show them).
std::string reversed(const std::string& name) {
  const std::size_t colon = name.rfind(": ");
  const std::size_t dash = name.find(" - ", colon == std::string::npos ? 0 : colon);
  if (colon == std::string::npos || dash == std::string::npos) return name;
  const std::string tail = " (Wilcoxon)";
  std::string right = name.substr(dash + 3), suffix;
  if (right.ends_with(tail)) {
    suffix = tail;
    right.resize(right.size() - tail.size());
  }
  return name.substr(0, colon + 2) + right + " - " + name.substr(colon + 2, dash - colon - 2) +
         suffix;
}

void remove_study(const std::filesystem::path& db) {
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
    std::error_code ignored;
    std::filesystem::remove(db.string() + suffix, ignored);
  }
}

}  // namespace

power::PowerReport pipeline_power(const Protocol& protocol, const PipelinePowerOptions& options,
                                  const std::function<void(int, int)>& progress) {
  const power::PowerOptions& o = options.power;
  if (o.n.empty()) throw std::invalid_argument("no N to compute the power for");
  if (o.sims < 1) throw std::invalid_argument("sims must be 1 or more");
  std::string planned;
  for (const Factor& f : protocol.factors) planned += (planned.empty() ? "" : ":") + f.name;
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
  for (std::size_t k = 0; k < o.n.size(); ++k) {
    const auto start = std::chrono::steady_clock::now();
    for (int s = 0; s < o.sims; ++s) {
      const std::filesystem::path db =
          dir / ("handlab-power-" + std::to_string(o.n[k]) + "-" + std::to_string(s) + "-" +
                 std::to_string(util::splitmix64(o.seed) % 100000) + ".db");
      remove_study(db);
      SimulationOptions so;
      so.participants = o.n[k];
      so.seed = util::splitmix64(
          o.seed ^ util::splitmix64(std::uint64_t(o.n[k]) * 1000003ull + std::uint64_t(s)));
      so.jobs = std::max(1, o.threads);
      so.world = options.world;
      try {
        simulate_study(protocol, db.string(), so);
        outcomes[k].push_back(outcome_of(analyze_study_database(db.string()), planned, o));
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
  auto known = [](const std::vector<std::string>& names, const std::string& name, bool contrast) {
    for (const std::string& n : names)
      if (n == name || (contrast && reversed(name) == n)) return true;
    return false;
  };
  for (const auto& per_n : outcomes)
    for (const Outcome& out : per_n) {
      for (const auto& [name, _] : out.effects)
        if (!known(effects, name, false)) effects.push_back(name);
      for (const auto& [name, _] : out.contrasts)
        if (!known(contrasts, name, true)) contrasts.push_back(name);
    }
  power::PowerReport report = power::empty_report(effects, contrasts, o.n, o.sims, o.alpha);
  std::vector<std::string> examples;
  for (std::size_t k = 0; k < o.n.size(); ++k) {
    std::vector<long> effect_hits(effects.size(), 0), contrast_hits(contrasts.size(), 0);
    int warnings = 0;
    for (Outcome out : outcomes[k]) {
      auto count = [&](const std::vector<std::string>& names, std::vector<long>& hits,
                       const std::vector<std::pair<std::string, bool>>& seen, bool contrast) {
        std::size_t found = 0;
        for (std::size_t i = 0; i < names.size(); ++i)
          for (const auto& [name, rejected] : seen)
            if (name == names[i] || (contrast && reversed(name) == names[i])) {
              hits[i] += rejected;
              ++found;
              break;
            }
        return found == names.size();
      };
      const bool all = count(effects, effect_hits, out.effects, false) &
                       count(contrasts, contrast_hits, out.contrasts, true);
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
  report.notes.push_back(std::string("pipeline: whole simulated studies on the ") +
                         (options.world == WorldKind::kSoftHand ? "soft hand" : "grasp proxy") +
                         ", analysed by analyze --db");
  return report;
}

}  // namespace handlab::studies
