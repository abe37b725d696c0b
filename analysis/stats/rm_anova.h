// Repeated-measures ANOVA by the multivariate approach with type 3 sums of squares, as
// afex::aov_ez computes it through car::Anova.mlm, with Mauchly's test and the
// Greenhouse-Geisser and Huynh-Feldt corrections.
#pragma once

#include <string>
#include <vector>

#include "analysis/stats/rm_data.h"

namespace handlab::stats {

struct AnovaEffect {
  std::string effect;  // factor names joined by ':', between terms first ("treatment:phase")
  double df_num = 0, df_den = 0;
  double ss = 0, ss_error = 0, mse = 0;
  double f = 0, p = 0;
  double pes = 0, ges = 0;
  // NaN for effects with one numerator df per between df (no sphericity to test).
  double mauchly_w, mauchly_p;
  double eps_gg, eps_hf;  // eps_hf as computed: it can exceed 1
  double p_gg, p_hf;      // p with df scaled by eps_gg and min(1, eps_hf)
};

struct AnovaResult {
  AnovaEffect intercept;
  std::vector<AnovaEffect> effects;  // afex's order: by within effect, then between term
  int n_subjects = 0;
};

AnovaResult rm_anova(const RmData& data);

}  // namespace handlab::stats
