# Times in R the analysis handlab's BM_FullStudyAnalysis times: afex::aov_ez with Mauchly and
# GG/HF corrections, emmeans pairs with Tukey for every within effect, per-cell descriptives.
#   Rscript scripts/bench_analysis.R FILE.csv [REPEATS]
suppressPackageStartupMessages({ library(afex); library(emmeans) })
args <- commandArgs(trailingOnly = TRUE)
d <- read.csv(args[1])
repeats <- if (length(args) > 1) as.integer(args[2]) else 5
d$manipulation <- factor(d$manipulation, levels = c("Gross", "Fine"))
d$strategy <- factor(d$strategy, levels = c("Naive", "Ours"))
d$repetition <- factor(d$repetition)
afex_options(emmeans_model = "multivariate")
analysis <- function() {
  fit <- suppressMessages(aov_ez("participant", "time", d, within = c("manipulation", "strategy", "repetition"), type = 3))
  s <- summary(fit)                                   # ANOVA + Mauchly + GG/HF
  effects <- list("manipulation", "strategy", "repetition", c("manipulation", "strategy"),
                  c("manipulation", "repetition"), c("strategy", "repetition"),
                  c("manipulation", "strategy", "repetition"))
  ph <- lapply(effects, function(e) summary(pairs(emmeans(fit, e)), adjust = "tukey"))
  desc <- aggregate(time ~ manipulation + strategy + repetition, d, function(x)
    c(n = length(x), mean = mean(x), sd = sd(x), se = sd(x) / sqrt(length(x)), quantile(x, c(0, .25, .5, .75, 1))))
  invisible(list(s, ph, desc))
}
analysis()  # warm-up
times <- sapply(seq_len(repeats), function(i) system.time(analysis())[["elapsed"]])
cat(sprintf("R full analysis, N = %d: median %.1f ms over %d runs\n", length(unique(d$participant)),
            1000 * median(times), repeats))
