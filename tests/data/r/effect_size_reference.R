# Reference values for analysis/stats/effect_size.h: partial eta squared and paired d_z with
# their 95 % intervals from the noncentral F and t, by base R's pf and pt (ncp) and uniroot,
# as MBESS's conf.limits.ncf / ci.pvaf and conf.limits.nct compute them.
# Run: Rscript tests/data/r/effect_size_reference.R > tests/data/r/effect_size_reference.json
ncp_bound <- function(cdf, target, upper) {
  if (cdf(0) <= target) return(0)
  uniroot(function(x) cdf(x) - target, c(0, upper), tol = 1e-13)$root
}
f_case <- function(f, df1, df2) {
  cdf <- function(l) pf(f, df1, df2, ncp = l)
  lo <- ncp_bound(cdf, 0.975, 1000); hi <- ncp_bound(cdf, 0.025, 1000)
  eta <- function(l) l / (l + df1 + df2 + 1)
  sprintf('{"F": %.17g, "df1": %.17g, "df2": %.17g, "pes": %.17g, "low": %.17g, "high": %.17g}',
          f, df1, df2, f * df1 / (f * df1 + df2), eta(lo), eta(hi))
}
t_case <- function(t, df) {
  cdf <- function(d) pt(t, df, ncp = d)
  lo <- uniroot(function(d) cdf(d) - 0.975, c(t - 40, t + 40), tol = 1e-13)$root
  hi <- uniroot(function(d) cdf(d) - 0.025, c(t - 40, t + 40), tol = 1e-13)$root
  n <- df + 1
  sprintf('{"t": %.17g, "df": %.17g, "dz": %.17g, "low": %.17g, "high": %.17g}',
          t, df, t / sqrt(n), lo / sqrt(n), hi / sqrt(n))
}
cat('{"R": "', R.version.string, '",\n"F": [\n', sep = "")
cat(paste(c(f_case(8.78, 1, 19), f_case(3.52^2, 1, 19), f_case(2.1, 3, 57),
            f_case(0.4, 1, 19), f_case(14.25, 2.6, 49.4)), collapse = ",\n"))
cat('\n],\n"t": [\n')
cat(paste(c(t_case(3.52, 19), t_case(-1.96, 19), t_case(0.3, 9), t_case(7.5, 29)),
          collapse = ",\n"))
cat('\n]}\n')
