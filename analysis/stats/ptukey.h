// The studentized range distribution, as R's ptukey (Copenhaver & Holland 1988, AS 190
// lineage): P(Q < q) for the range of `means` normal means with `df` error degrees of freedom.
#pragma once

#include <memory>

namespace handlab::stats {

// ranges: number of independent ranges (R's nranges, 1 for Tukey's test).
double ptukey_lower(double q, double means, double df, double ranges = 1.0);
// The upper tail, computed like R as 1 - lower (so values below ~1e-12 are noise, as in R).
double ptukey_upper(double q, double means, double df, double ranges = 1.0);

// Many upper tails of one family (same means and df), as Tukey's test of every pair of k
// means needs. R's outer quadrature is kept node for node, with its weights computed once;
// the range probability W(w) of its inner integral comes from an interpolant made once per
// number of means (~1e-15 from R's wprob). Cheaper than ptukey_upper from the first call.
class TukeyFamily {
 public:
  TukeyFamily(double means, double df, double ranges = 1.0);
  double upper(double q) const;

 private:
  struct RangeTable;
  struct OuterNodes;
  double means_, df_, ranges_;
  std::shared_ptr<const RangeTable> table_;
  std::shared_ptr<const OuterNodes> nodes_;
};

}  // namespace handlab::stats
