#include "study_data.h"

#include <cmath>
#include <cstdio>

#include "core/util/portable_random.h"

namespace handlab::bench {

std::string synthetic_study_csv(int participants, unsigned seed) {
  util::PortableRandom random(seed);
  auto normal = [&] {  // Box-Muller
    const double u = 1.0 - random.uniform(), v = random.uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v);
  };
  std::string csv = "participant,manipulation,strategy,repetition,time\n";
  char line[128];
  for (int p = 1; p <= participants; ++p) {
    const double speed = std::exp(0.25 * normal());
    for (const char* m : {"Gross", "Fine"})
      for (const char* s : {"Naive", "Ours"})
        for (int r = 1; r <= 5; ++r) {
          double t = m[0] == 'G' ? 7.5 : (s[0] == 'N' ? 18.0 : 12.0);
          t *= speed * (1.0 + 0.15 * std::exp(-(r - 1))) * std::exp(0.15 * normal());
          std::snprintf(line, sizeof line, "P%05d,%s,%s,%d,%.3f\n", p, m, s, r, t);
          csv += line;
        }
  }
  return csv;
}

analysis::LongTable synthetic_study_table(int participants, unsigned seed) {
  return analysis::LongTable::parse_csv(synthetic_study_csv(participants, seed), "synthetic");
}

}  // namespace handlab::bench
