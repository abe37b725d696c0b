// Power answered by the whole pipeline (`handlab-cli power --pipeline`): for every N, whole
// simulated studies (docs/simulated-participants.md: closed-loop participants, retargeting,
// the soft hand or the grasp proxy, the task, the study database) analysed by analyze --db;
// the share of studies with a significant result is the power. Slow: a study of 20 on the soft
// hand takes minutes, so `sims` is small and the report gives the time.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "analysis/power/power_analysis.h"
#include "studies/protocol/protocol.h"
#include "studies/session/trial_driver.h"

namespace handlab::studies {

struct PipelinePowerOptions {
  power::PowerOptions power;  // n, sims, alpha, seed, correction; threads: sessions side by side
  WorldKind world = WorldKind::kSoftHand;
  std::string work_dir;  // where each study's database is written, then removed
  // Analyse the studies a Slurm series merged in this folder (power --pipeline --slurm)
  // instead of simulating them: each must be there (empty: simulate).
  std::string from_dir;
};

// The studies a pipeline power runs: for every N, `sims` studies, each with its own seed
// derived from the power's seed, N and its index.
struct PipelineStudy {
  int participants = 0;
  std::uint64_t seed = 0;
};
std::vector<std::vector<PipelineStudy>> pipeline_studies(const power::PowerOptions& options);

// `progress(done, total)` after every simulated study.
power::PowerReport pipeline_power(const Protocol& protocol, const PipelinePowerOptions& options,
                                  const std::function<void(int, int)>& progress = {});

}  // namespace handlab::studies
