// Google Benchmark's main, plus `--write-study-csv FILE N` to write the synthetic study data
// the analysis benchmark uses, so R can be timed on the same numbers.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include <benchmark/benchmark.h>

#include "study_data.h"

int main(int argc, char** argv) {
  if (argc == 4 && std::strcmp(argv[1], "--write-study-csv") == 0) {
    std::ofstream(argv[2]) << handlab::bench::synthetic_study_csv(std::atoi(argv[3]), 2021);
    return 0;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
