#include "analysis/report/analysis_output.h"

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "core/util/json_writer.h"

namespace handlab::analysis {
namespace {

std::string fixed(double v, int decimals) {
  if (std::isnan(v)) return "NA";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

void write_at(util::JsonWriter& json, const char* key,
              const std::vector<std::pair<std::string, std::string>>& at) {
  json.key(key).begin_object();
  for (const auto& [factor, level] : at) json.field(factor, level);
  json.end_object();
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& i : items) out += (out.empty() ? "" : ", ") + i;
  return out;
}

}  // namespace

std::string apa_p(double p) {
  if (std::isnan(p)) return "p = NA";
  if (p < 0.001) return "p < .001";
  std::string s = fixed(p, 3);
  if (s == "1.000") return "p > .999";
  return "p = " + s.substr(s.find('.'));
}

std::string apa_unit(double value, int decimals) {
  std::string s = fixed(value, decimals);
  if (s.rfind("0.", 0) == 0) return s.substr(1);
  if (s.rfind("-0.", 0) == 0) return "-" + s.substr(2);
  return s;
}

std::string apa_df(double df) {
  return std::abs(df - std::round(df)) < 1e-9 ? fixed(df, 0) : fixed(df, 2);
}

void write_json(const AnalysisReport& r, std::ostream& out) {
  util::JsonWriter json(out);
  json.begin_object();
  json.field("source", r.source);
  json.key("design").begin_object();
  json.field("subject", r.request.design.subject);
  json.field("dv", r.request.design.dv);
  json.key("within").string_array(r.request.design.within);
  json.key("between").string_array(r.request.design.between);
  json.key("covariates").string_array(r.request.design.covariates);
  json.key("covariate_means").begin_array();
  for (double m : r.covariate_means) json.value(m);
  json.end_array();
  json.field("n_subjects", r.n_subjects);
  json.key("dropped_subjects").string_array(r.dropped_subjects);
  json.key("warnings").string_array(r.warnings);
  json.end_object();

  if (r.nonparametric()) {
    json.key("friedman").begin_array();
    for (const auto& f : r.friedman) {
      json.begin_object().field("dv", f.dv).field("chisq", f.result.chisq).field("df", f.result.df);
      json.field("p", f.result.p).field("kendall_w", f.result.kendall_w).field("n", f.result.n);
      json.key("dropped_subjects").string_array(f.dropped_subjects);
      json.end_object();
    }
    json.end_array();
    json.key("wilcoxon").begin_array();
    for (const auto& w : r.wilcoxon) {
      json.begin_object().field("dv", w.dv).field("contrast", w.contrast).field("V", w.result.v);
      json.field("n", w.result.n).field("exact", w.result.exact).field("p_none", w.result.p);
      json.field("p_bonferroni", w.p_bonferroni).field("p_holm", w.p_holm).end_object();
    }
    json.end_array();
    json.end_object();
    return;
  }

  json.key("anova").begin_array();
  for (const auto& e : r.anova.effects) {
    json.begin_object()
        .field("effect", e.effect)
        .field("df_num", e.df_num)
        .field("df_den", e.df_den);
    json.field("ss", e.ss)
        .field("ss_error", e.ss_error)
        .field("mse", e.mse)
        .field("F", e.f)
        .field("p", e.p);
    json.field("pes", e.pes)
        .field("ges", e.ges)
        .field("mauchly_W", e.mauchly_w)
        .field("mauchly_p", e.mauchly_p);
    json.field("eps_gg", e.eps_gg)
        .field("eps_hf", e.eps_hf)
        .field("p_gg", e.p_gg)
        .field("p_hf", e.p_hf);
    json.end_object();
  }
  json.end_array();

  json.key("emmeans").begin_array();
  for (std::size_t i = 0; i < r.posthoc.size(); ++i) {
    for (const auto& m : r.posthoc[i].means) {
      json.begin_object().field("effect",
                                r.request.posthoc.empty() ? std::string() : r.request.posthoc[i]);
      write_at(json, "at", m.at);
      json.field("emmean", m.estimate).field("se", m.se).field("df", m.df);
      json.field("lower_cl", m.lower_cl).field("upper_cl", m.upper_cl).end_object();
    }
  }
  json.end_array();

  json.key("posthoc").begin_array();
  for (const auto& ph : r.posthoc) {
    for (const auto& c : ph.contrasts) {
      json.begin_object().field("effect", c.effect).field("contrast", c.contrast);
      write_at(json, "by", c.by);
      json.field("estimate", c.estimate).field("se", c.se).field("df", c.df).field("t", c.t);
      json.field("p_none", c.p_none)
          .field("p_tukey", c.p_tukey)
          .field("p_bonferroni", c.p_bonferroni);
      json.field("p_holm", c.p_holm)
          .field("p_bonferroni_all", c.p_bonferroni_all)
          .field("p_holm_all", c.p_holm_all);
      json.end_object();
    }
  }
  json.end_array();

  json.key("descriptives").begin_array();
  for (const auto& c : r.descriptives) {
    json.begin_object();
    write_at(json, "cell", c.cell);
    json.field("n", c.d.n).field("mean", c.d.mean).field("sd", c.d.sd).field("se", c.d.se);
    json.field("median", c.d.median).field("q1", c.d.q1).field("q3", c.d.q3);
    json.field("min", c.d.min).field("max", c.d.max).end_object();
  }
  json.end_array();
  json.end_object();
}

void write_text(const AnalysisReport& r, std::ostream& out) {
  const auto& d = r.request.design;
  out << "Data: " << r.source << "\n";
  for (const auto& w : r.warnings) out << "Warning: " << w << "\n";
  if (r.nonparametric()) {
    out << "Participants: " << r.n_subjects << "; conditions: " << join(d.within) << "\n";
    for (const auto& f : r.friedman) {
      out << "\n"
          << f.dv << ": Friedman χ²(" << apa_df(f.result.df) << ", N = " << f.result.n
          << ") = " << fixed(f.result.chisq, 2) << ", " << apa_p(f.result.p)
          << ", Kendall's W = " << apa_unit(f.result.kendall_w) << "\n";
      for (const auto& w : r.wilcoxon) {
        if (w.dv != f.dv) continue;
        out << "  " << std::left << std::setw(32) << w.contrast << " V = " << fixed(w.result.v, 1)
            << ", n = " << w.result.n << (w.result.exact ? " (exact)" : "") << ", "
            << apa_p(w.result.p) << ", Bonferroni " << apa_p(w.p_bonferroni) << ", Holm "
            << apa_p(w.p_holm) << "\n";
      }
    }
    return;
  }
  out << "Repeated-measures ANOVA of " << d.dv << " (type 3 sums of squares), N = " << r.n_subjects;
  if (!r.dropped_subjects.empty()) out << " (dropped: " << join(r.dropped_subjects) << ")";
  out << "\nWithin: " << join(d.within);
  if (!d.between.empty()) out << "; between: " << join(d.between);
  if (!d.covariates.empty()) out << "; covariates (centred): " << join(d.covariates);
  out << "\n\n";
  for (const auto& e : r.anova.effects) {
    out << std::left << std::setw(34) << e.effect << " F(" << apa_df(e.df_num) << ", "
        << apa_df(e.df_den) << ") = " << fixed(e.f, 2) << ", " << apa_p(e.p)
        << ", ηp² = " << apa_unit(e.pes) << ", ηG² = " << apa_unit(e.ges) << "\n";
    if (!std::isnan(e.eps_gg)) {
      out << std::setw(34) << ""
          << " Mauchly's W = " << apa_unit(e.mauchly_w, 3) << ", " << apa_p(e.mauchly_p)
          << "; Greenhouse-Geisser ε = " << apa_unit(e.eps_gg, 3) << ", F("
          << apa_df(e.df_num * e.eps_gg) << ", " << apa_df(e.df_den * e.eps_gg) << "), "
          << apa_p(e.p_gg) << "; Huynh-Feldt ε = " << apa_unit(std::min(1.0, e.eps_hf), 3) << ", "
          << apa_p(e.p_hf) << "\n";
    }
  }
  for (const auto& ph : r.posthoc) {
    if (ph.contrasts.empty()) continue;
    out << "\nPairwise comparisons, " << ph.contrasts.front().effect;
    if (!ph.contrasts.front().by.empty()) {
      out << " at each level of";
      for (const auto& [factor, level] : ph.contrasts.front().by) out << " " << factor;
    }
    out << " (t tests on participant means; p adjusted by Tukey / Holm):\n";
    for (const auto& c : ph.contrasts) {
      std::string label = c.contrast;
      for (const auto& [factor, level] : c.by) label += ", " + factor + " = " + level;
      out << "  " << std::left << std::setw(40) << label << " Δ = " << fixed(c.estimate, 3)
          << ", t(" << apa_df(c.df) << ") = " << fixed(c.t, 2) << ", " << apa_p(c.p_none)
          << ", Tukey " << apa_p(c.p_tukey) << ", Holm " << apa_p(c.p_holm) << "\n";
    }
  }
  out << "\nDescriptives (participant cell means):\n";
  for (const auto& c : r.descriptives) {
    std::string label;
    for (const auto& [factor, level] : c.cell) label += (label.empty() ? "" : " ") + level;
    out << "  " << std::left << std::setw(24) << label << " n = " << c.d.n
        << ", M = " << fixed(c.d.mean, 3) << ", SD = " << fixed(c.d.sd, 3)
        << ", Mdn = " << fixed(c.d.median, 3) << ", IQR = [" << fixed(c.d.q1, 3) << ", "
        << fixed(c.d.q3, 3) << "]\n";
  }
}

}  // namespace handlab::analysis
