# The simulation loop of `handlab-cli power` written in R with afex and emmeans, for the
# benchmark in docs/performance.md (R is for this benchmark only; handlab does not need it).
# Usage: Rscript scripts/power-benchmark.R SIMS N [N ...]
# For each N, simulates SIMS studies of N participants of the 2x2x5 design of
# studies/fine-manipulation-2021-effects.json and analyses each as handlab does (afex aov_ez
# with the sphericity correction, emmeans Tukey pairwise comparisons of strategy:manipulation),
# and prints the seconds taken and the interaction's power per N, then the total.
# The benchmark in docs/performance.md: Rscript scripts/power-benchmark.R 1000 $(seq 10 2 40)
suppressPackageStartupMessages({
  library(afex)
  library(emmeans)
  library(MASS)
})
args <- commandArgs(trailingOnly = TRUE)
sims <- if (length(args) >= 1) as.integer(args[1]) else 20L
ns <- if (length(args) >= 2) as.integer(args[-1]) else 20L
set.seed(1)
afex_options(check_contrasts = TRUE)
emm_options(msg.interaction = FALSE)
conditions <- expand.grid(strategy = c("naive", "ours"), manipulation = c("gross", "fine"),
                          repetition = 1:5)
cond_mean <- c("naive.gross" = 8.0, "ours.gross" = 8.2084, "naive.fine" = 9.9524,
               "ours.fine" = 8.5444)
rep_effect <- c(1.606, 0.276, -0.313, -0.664, -0.904)
mu <- cond_mean[paste(conditions$strategy, conditions$manipulation, sep = ".")] +
  rep_effect[conditions$repetition]
k <- length(mu)
sigma <- 4^2 * (matrix(0.5, k, k) + diag(0.5, k))
simulate <- function(n) {
  hits <- 0
  for (s in seq_len(sims)) {
    y <- mvrnorm(n, mu, sigma)
    d <- data.frame(participant = factor(rep(seq_len(n), times = k)),
                    strategy = rep(conditions$strategy, each = n),
                    manipulation = rep(conditions$manipulation, each = n),
                    repetition = factor(rep(conditions$repetition, each = n)),
                    completion_time_s = as.vector(y))
    fit <- suppressMessages(aov_ez("participant", "completion_time_s", d,
                                   within = c("strategy", "manipulation", "repetition")))
    a <- anova(fit, correction = "GG")
    if (a["strategy:manipulation", "Pr(>F)"] < 0.05) hits <- hits + 1
    pairs(emmeans(fit, ~ strategy:manipulation), adjust = "tukey")
  }
  hits / sims
}
total <- Sys.time()
for (n in ns) {
  start <- Sys.time()
  power <- simulate(n)
  seconds <- as.numeric(difftime(Sys.time(), start, units = "secs"))
  cat(sprintf("R afex+emmeans: N = %d, %d simulations in %.2f s (%.1f ms each); interaction power %.3f\n",
              n, sims, seconds, 1000 * seconds / sims, power))
}
cat(sprintf("R afex+emmeans: %d simulations in all, %.1f s\n", sims * length(ns),
            as.numeric(difftime(Sys.time(), total, units = "secs"))))
