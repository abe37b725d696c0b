#include "studies/report/report_tables.h"

#include <cmath>

#include "studies/report/report_text.h"

namespace handlab::studies {

using namespace report_text;

bool sphericity_corrected(const stats::AnovaEffect& e) {
  return std::isfinite(e.mauchly_p) && e.mauchly_p < kAlpha;
}

bool anova_significant(const stats::AnovaEffect& e) {
  return (sphericity_corrected(e) ? e.p_gg : e.p) < kAlpha;
}

namespace {

// "1, 19" or, corrected, "1.54, 29.26" (df × ε).
ReportLine df_pair(const stats::AnovaEffect& e, const std::string& key, bool corrected) {
  if (corrected)
    return {number(e.df_num * e.eps_gg, 2, key + "df_num*" + key + "eps_gg"), words(", "),
            number(e.df_den * e.eps_gg, 2, key + "df_den*" + key + "eps_gg")};
  return {number(e.df_num, 0, key + "df_num"), words(", "), number(e.df_den, 0, key + "df_den")};
}

}  // namespace

ReportTable anova_table(const analysis::AnalysisReport& r, const std::string& root) {
  ReportTable t;
  t.header = {"Effect", "df", "F", "p", "η²G", "ε (GG)", "Mauchly's W", "p (Mauchly)"};
  for (std::size_t i = 0; i < r.anova.effects.size(); ++i) {
    const stats::AnovaEffect& e = r.anova.effects[i];
    const std::string key = root + "/anova/" + std::to_string(i) + "/";
    const bool tested = std::isfinite(e.mauchly_p);
    const bool corrected = sphericity_corrected(e);
    t.rows.push_back(
        {{words(effect_name(e.effect))},
         df_pair(e, key, corrected),
         {number(e.f, 2, key + "F")},
         corrected ? p_cell(e.p_gg, key + "p_gg") : p_cell(e.p, key + "p"),
         {bounded(e.ges, 3, key + "ges")},
         tested ? ReportLine{bounded(e.eps_gg, 3, key + "eps_gg")} : ReportLine{words("–")},
         tested ? ReportLine{bounded(e.mauchly_w, 3, key + "mauchly_W")} : ReportLine{words("–")},
         tested ? p_cell(e.mauchly_p, key + "mauchly_p") : ReportLine{words("–")}});
  }
  t.note =
      "Where Mauchly's test rejects sphericity (p < .05) the df and p are Greenhouse–Geisser "
      "corrected (df × ε). η²G: generalised eta squared. Effects with one numerator df have no "
      "sphericity to test (–).";
  return t;
}

ReportLine anova_sentence(const std::string& key, const stats::AnovaEffect& e, bool corrected,
                          const std::string& dv) {
  const bool interaction = e.effect.find(':') != std::string::npos;
  ReportLine line = {words(std::string("There was a significant ") +
                           (interaction ? "interaction " + effect_name(e.effect)
                                        : "main effect of " + effect_name(e.effect)) +
                           " on " + dv + ", F(")};
  append(line, df_pair(e, key, corrected));
  append(line, {words(") = "), number(e.f, 2, key + "F"), words(", ")});
  append(line, corrected ? p_line(e.p_gg, key + "p_gg") : p_line(e.p, key + "p"));
  append(line, {words(", η²G = "), bounded(e.ges, 3, key + "ges")});
  if (corrected)
    append(line,
           {words(" (Greenhouse–Geisser ε = "), bounded(e.eps_gg, 3, key + "eps_gg"), words(")")});
  append(line, {words(".")});
  return line;
}

ReportTable friedman_table(const analysis::AnalysisReport& q, const std::string& root) {
  ReportTable f;
  f.header = {"Item", "χ²", "df", "p", "Kendall's W", "n"};
  for (std::size_t i = 0; i < q.friedman.size(); ++i) {
    const analysis::FriedmanItem& item = q.friedman[i];
    const std::string key = root + "/friedman/" + std::to_string(i) + "/";
    f.rows.push_back({{words(display(item.dv))},
                      {number(item.result.chisq, 2, key + "chisq")},
                      {number(item.result.df, 0, key + "df")},
                      p_cell(item.result.p, key + "p"),
                      {bounded(item.result.kendall_w, 3, key + "kendall_w")},
                      {count(item.result.n, key + "n")}});
  }
  return f;
}

ReportLine friedman_sentence(const analysis::AnalysisReport& q, std::size_t i,
                             const std::string& root, const std::string& what) {
  const analysis::FriedmanItem& item = q.friedman[i];
  const std::string key = root + "/friedman/" + std::to_string(i) + "/";
  const bool significant = item.result.p < kAlpha;
  ReportLine line = {
      words(display(item.dv) + ": " + what + " " +
            (significant ? "differed significantly" : "did not differ significantly") +
            " across conditions, χ²("),
      number(item.result.df, 0, key + "df"),
      words(", N = "),
      count(item.result.n, key + "n"),
      words(") = "),
      number(item.result.chisq, 2, key + "chisq"),
      words(", ")};
  append(line, p_line(item.result.p, key + "p"));
  append(line, {words(".")});
  if (!significant) return line;
  std::vector<std::size_t> pairs;
  for (std::size_t w = 0; w < q.wilcoxon.size(); ++w)
    if (q.wilcoxon[w].dv == item.dv && q.wilcoxon[w].p_bonferroni < kAlpha) pairs.push_back(w);
  if (pairs.empty()) {
    append(line,
           {words(" No pairwise Wilcoxon test was significant after the Bonferroni adjustment.")});
    return line;
  }
  append(line, {words(" Wilcoxon signed-rank tests (Bonferroni-adjusted): ")});
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const analysis::WilcoxonPair& w = q.wilcoxon[pairs[k]];
    const std::string wkey = root + "/wilcoxon/" + std::to_string(pairs[k]) + "/";
    append(line, {words(std::string(k ? "; " : "") + levels_name(w.first) + " against " +
                        levels_name(w.second) + ", V = "),
                  number(w.result.v, 1, wkey + "V"), words(", ")});
    append(line, p_line(w.p_bonferroni, wkey + "p_bonferroni"));
  }
  append(line, {words(".")});
  return line;
}

ReportTable wilcoxon_table(const analysis::AnalysisReport& q, const std::string& root) {
  ReportTable w;
  w.header = {"Item", "Contrast", "V", "n", "p", "p (Bonferroni)"};
  for (std::size_t i = 0; i < q.wilcoxon.size(); ++i) {
    const analysis::WilcoxonPair& pair = q.wilcoxon[i];
    const std::string key = root + "/wilcoxon/" + std::to_string(i) + "/";
    w.rows.push_back({{words(display(pair.dv))},
                      {words(levels_name(pair.first) + " − " + levels_name(pair.second))},
                      {number(pair.result.v, 1, key + "V")},
                      {count(pair.result.n, key + "n")},
                      p_cell(pair.result.p, key + "p_none"),
                      p_cell(pair.p_bonferroni, key + "p_bonferroni")});
  }
  w.note = "n: pairs with a non-zero difference.";
  return w;
}

}  // namespace handlab::studies
