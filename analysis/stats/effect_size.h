// Effect sizes of the tests a study reports, with confidence intervals from the noncentral
// distributions (Steiger & Fouladi 1997; Steiger 2004; Smithson 2003): so that a replication
// is judged by how large an effect is, not by whether p fell below .05.
#pragma once

namespace handlab::stats {

struct EffectInterval {
  double low = 0.0, high = 0.0;
};

// Partial eta squared of an F test: F df1 / (F df1 + df2) (the same with the sphericity
// correction, which scales both dfs).
double partial_eta_squared(double f, double df1, double df2);

// Its `level` interval: the noncentrality lambda of F(df1, df2, lambda) whose cdf at `f` is
// (1 + level) / 2 and (1 - level) / 2 (0 where no lambda reaches it), each as
// lambda / (lambda + df1 + df2 + 1), as MBESS's ci.pvaf converts it.
EffectInterval partial_eta_squared_interval(double f, double df1, double df2, double level = 0.95);

// d_z of a within-participants contrast of n people (the mean difference over the
// differences' standard deviation): t / sqrt(n). A paired t test has df = n - 1; with g
// groups between participants the contrast's df is n - g.
double paired_dz(double t, double n);

// Its `level` interval from the noncentral t with `df`: delta / sqrt(n) at the deltas whose
// cdf at `t` is (1 + level) / 2 and (1 - level) / 2.
EffectInterval paired_dz_interval(double t, double df, double n, double level = 0.95);

}  // namespace handlab::stats
