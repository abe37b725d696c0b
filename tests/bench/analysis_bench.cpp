// The full analysis of the study's 2x2x5 design (ANOVA + sphericity + post hoc for every
// within effect + descriptives), from an in-memory long table.
#include <benchmark/benchmark.h>

#include "analysis/report/study_analysis.h"
#include "study_data.h"

namespace {

void BM_FullStudyAnalysis(benchmark::State& state) {
  const auto table = handlab::bench::synthetic_study_table(int(state.range(0)), 2021);
  handlab::analysis::AnalysisRequest request;
  request.design = {"participant", "time", {"manipulation", "strategy", "repetition"}, {}, {}, {}};
  for (auto _ : state) benchmark::DoNotOptimize(handlab::analysis::run_analysis(table, request));
  state.counters["participants"] = double(state.range(0));
}
BENCHMARK(BM_FullStudyAnalysis)->Arg(20)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace
