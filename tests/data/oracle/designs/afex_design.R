# The completion-time ANOVA of an exported study (trials.csv) as R's afex computes it, for the
# design tests (tests/app/design_cli_test.cpp):
#   Rscript afex_design.R trials.csv OUT.json [BETWEEN]
# Within: the protocol's factors as the export's columns between "order" and "repetition",
# then repetition; BETWEEN, if given, a between-participants column. Timed-out trials count
# at the trial's limit, as the export holds them; skipped trials (no time) are left out.
suppressPackageStartupMessages({
  library(afex)
  library(jsonlite)
})
args <- commandArgs(trailingOnly = TRUE)
trials <- read.csv(args[1], stringsAsFactors = FALSE, colClasses = "character")
columns <- names(trials)
within <- c(columns[(which(columns == "order") + 1):(which(columns == "repetition") - 1)],
            "repetition")
between <- if (length(args) >= 3) args[3] else NULL
trials <- trials[trials$completion_time_s != "", ]
trials$completion_time_s <- as.numeric(trials$completion_time_s)
for (f in c(within, between)) trials[[f]] <- factor(trials[[f]], levels = unique(trials[[f]]))

fit <- aov_ez(id = "participant", dv = "completion_time_s", data = trials, within = within,
              between = between, type = 3, include_aov = FALSE)
univariate <- summary(fit$Anova, multivariate = FALSE)
table <- univariate$univariate.tests
es <- anova(fit, es = c("pes", "ges"), correction = "none")
sphericity <- univariate$sphericity.tests
corrections <- univariate$pval.adjustments

number <- function(x) if (is.na(x)) "NA" else signif(x, 15)
effects <- lapply(rownames(table), function(name) {
  row <- table[name, ]
  e <- list(effect = name, num_df = number(row[["num Df"]]), den_df = number(row[["den Df"]]),
            SS = number(row[["Sum Sq"]]), SS_error = number(row[["Error SS"]]),
            MSE = number(row[["Error SS"]] / row[["den Df"]]), F = number(row[["F value"]]),
            p = number(row[["Pr(>F)"]]))
  if (name != "(Intercept)") {
    e$pes <- number(es[name, "pes"])
    e$ges <- number(es[name, "ges"])
  }
  tested <- !is.null(sphericity) && name %in% rownames(sphericity)
  e$mauchly_W <- if (tested) number(sphericity[name, "Test statistic"]) else "NA"
  e$mauchly_p <- if (tested) number(sphericity[name, "p-value"]) else "NA"
  corrected <- !is.null(corrections) && name %in% rownames(corrections)
  e$GG_eps <- if (corrected) number(corrections[name, "GG eps"]) else "NA"
  e$HF_eps_raw <- if (corrected) number(corrections[name, "HF eps"]) else "NA"
  e$p_GG <- if (corrected) number(corrections[name, "Pr(>F[GG])"]) else "NA"
  e$p_HF <- if (corrected) number(corrections[name, "Pr(>F[HF])"]) else "NA"
  e
})
out <- list(
  oracle = "afex_design.R v1",
  input = basename(args[1]),
  versions = list(R = R.version.string, afex = as.character(packageVersion("afex")),
                  car = as.character(packageVersion("car"))),
  call = sprintf("aov_ez(id = 'participant', dv = 'completion_time_s', within = c(%s)%s, type = 3)",
                 paste0("'", within, "'", collapse = ", "),
                 if (is.null(between)) "" else sprintf(", between = '%s'", between)),
  participants = length(unique(trials$participant)),
  effects = effects)
writeLines(toJSON(out, auto_unbox = TRUE, pretty = TRUE, digits = NA), args[2])
