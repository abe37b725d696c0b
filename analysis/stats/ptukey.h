// The studentized range distribution, as R's ptukey (Copenhaver & Holland 1988, AS 190
// lineage): P(Q < q) for the range of `means` normal means with `df` error degrees of freedom.
#pragma once

namespace handlab::stats {

// ranges: number of independent ranges (R's nranges, 1 for Tukey's test).
double ptukey_lower(double q, double means, double df, double ranges = 1.0);
// The upper tail, computed like R as 1 - lower (so values below ~1e-12 are noise, as in R).
double ptukey_upper(double q, double means, double df, double ranges = 1.0);

}  // namespace handlab::stats
