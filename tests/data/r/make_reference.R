# Reference results for handlab's statistics tests, computed with R 4.2 + afex 1.2 +
# emmeans 1.8 + car as Debian 12 packages them:
#   apt-get install r-base-core r-cran-afex r-cran-emmeans r-cran-car r-cran-jsonlite
#   Rscript tests/data/r/make_reference.R tests/data/r
# Writes, per case, CASE.csv (the data handlab reads) and CASE.json (what R computed).
suppressPackageStartupMessages({
  library(afex); library(emmeans); library(car); library(jsonlite)
})
args <- commandArgs(trailingOnly = TRUE)
out_dir <- if (length(args) > 0) args[1] else "."
set.seed(20261122)

num <- function(x) { x <- unname(x); ifelse(is.na(x), "NA", signif(x, 15)) }

univariate <- function(fit) {
  s <- summary(fit$Anova, multivariate = FALSE)
  u <- s$univariate.tests
  tab_none <- anova(fit, es = c("pes", "ges"), correction = "none")
  rows <- lapply(rownames(u), function(term) {
    r <- list(effect = term, num_df = num(u[term, "num Df"]), den_df = num(u[term, "den Df"]),
              SS = num(u[term, "Sum Sq"]), SS_error = num(u[term, "Error SS"]),
              F = num(u[term, "F value"]), p = num(u[term, "Pr(>F)"]))
    if (term %in% rownames(tab_none)) {
      r$pes <- num(tab_none[term, "pes"]); r$ges <- num(tab_none[term, "ges"])
    }
    if (!is.null(s$pval.adjustments) && term %in% rownames(s$pval.adjustments)) {
      a <- s$pval.adjustments
      r$GG_eps <- num(a[term, "GG eps"]); r$p_GG <- num(a[term, "Pr(>F[GG])"])
      r$HF_eps_raw <- num(a[term, "HF eps"]); r$p_HF <- num(a[term, "Pr(>F[HF])"])
    }
    if (!is.null(s$sphericity.tests) && term %in% rownames(s$sphericity.tests)) {
      r$mauchly_W <- num(s$sphericity.tests[term, "Test statistic"])
      r$mauchly_p <- num(s$sphericity.tests[term, "p-value"])
    }
    r
  })
  rows
}

pairs_table <- function(fit, specs, by = NULL) {
  em <- emmeans(fit, specs = specs, by = by, model = "multivariate")
  out <- list()
  for (adjust in c("none", "tukey", "bonferroni", "holm")) {
    p <- as.data.frame(summary(pairs(em), adjust = adjust))
    out[[adjust]] <- lapply(seq_len(nrow(p)), function(i) {
      r <- list(contrast = as.character(p$contrast[i]), estimate = num(p$estimate[i]), SE = num(p$SE[i]),
                df = num(p$df[i]), t = num(p$t.ratio[i]), p = num(p$p.value[i]))
      if (!is.null(by)) for (b in by) r[[b]] <- as.character(p[[b]][i])
      r
    })
  }
  out
}

# Case 1: unbalanced mixed design, 3 x 2 within, a 3-level between factor with groups of
# 5, 7 and 6, and a numeric covariate.
n <- 18
ids <- sprintf("S%02d", 1:n)
group <- rep(c("g1", "g2", "g3"), times = c(5, 7, 6))
age <- round(runif(n, 19, 45))
d <- expand.grid(A = c("a1", "a2", "a3"), B = c("b1", "b2"), id = ids, stringsAsFactors = FALSE)
d$G <- group[match(d$id, ids)]
d$age <- age[match(d$id, ids)]
subject <- rnorm(n, 0, 2)
effect_a <- c(a1 = 0, a2 = 1.5, a3 = 3)
d$y <- round(10 + subject[match(d$id, ids)] + effect_a[d$A] * (1 + 0.4 * (d$G == "g2")) +
             0.8 * (d$B == "b2") + 0.05 * d$age + rnorm(nrow(d), 0, 1 + (d$A == "a3")), 3)
d <- d[, c("id", "G", "age", "A", "B", "y")]
write.csv(d, file.path(out_dir, "mixed_unbalanced_covariate.csv"), row.names = FALSE)

r <- d
r$A <- factor(r$A, levels = c("a1", "a2", "a3")); r$B <- factor(r$B, levels = c("b1", "b2"))
r$G <- factor(r$G, levels = c("g1", "g2", "g3"))
r$age <- r$age - mean(age)  # centred on the participants' mean, as handlab does
fit <- suppressWarnings(suppressMessages(aov_ez("id", "y", r, within = c("A", "B"), between = "G",
                                                covariate = "age", factorize = FALSE, type = 3)))
case1 <- list(design = list(subject = "id", dv = "y", within = c("A", "B"), between = "G", covariate = "age"),
              effects = univariate(fit),
              emmeans_A = pairs_table(fit, "A"),
              emmeans_B_by_A = pairs_table(fit, "B", by = "A"))
write_json(case1, file.path(out_dir, "mixed_unbalanced_covariate.json"), auto_unbox = TRUE, pretty = TRUE, digits = NA)

# Case 2: 4 x 3 within, N = 15, each cell observed twice (afex averages, with a warning).
n <- 15
ids <- sprintf("P%02d", 1:n)
d <- expand.grid(rep = 1:2, D = c("d1", "d2", "d3"), C = c("c1", "c2", "c3", "c4"), id = ids, stringsAsFactors = FALSE)
subject <- rnorm(n, 0, 3)
effect_c <- c(c1 = 0, c2 = 0.5, c3 = 2, c4 = 2.5)
effect_d <- c(d1 = 0, d2 = -1, d3 = 1)
d$y <- round(20 + subject[match(d$id, ids)] * (1 + 0.3 * (d$C == "c4")) + effect_c[d$C] + effect_d[d$D] +
             0.7 * (d$C == "c3") * (d$D == "d3") + rnorm(nrow(d), 0, 1.5), 2)
d <- d[, c("id", "C", "D", "rep", "y")]
write.csv(d, file.path(out_dir, "within_4x3_replicates.csv"), row.names = FALSE)
r <- d
r$C <- factor(r$C, levels = c("c1", "c2", "c3", "c4")); r$D <- factor(r$D, levels = c("d1", "d2", "d3"))
fit <- suppressWarnings(suppressMessages(aov_ez("id", "y", r, within = c("C", "D"), type = 3, fun_aggregate = mean)))
case2 <- list(design = list(subject = "id", dv = "y", within = c("C", "D")),
              effects = univariate(fit),
              emmeans_CD = pairs_table(fit, c("C", "D")),
              emmeans_C_by_D = pairs_table(fit, "C", by = "D"))
write_json(case2, file.path(out_dir, "within_4x3_replicates.json"), auto_unbox = TRUE, pretty = TRUE, digits = NA)
cat("wrote reference cases to", out_dir, "\n")
