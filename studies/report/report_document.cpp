#include "studies/report/report_document.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "analysis/report/analysis_output.h"
#include "studies/report/report_tables.h"
#include "studies/report/report_text.h"

namespace handlab::studies {
namespace {

using namespace report_text;

// What came before the blocks: practice trials, which the analysis leaves out, or none.
std::string practice_clause(const Protocol& p) {
  if (p.practice_per_condition == 0) return ", with no practice trials";
  return ", after " + std::to_string(p.practice_per_condition) + " practice trial" +
         (p.practice_per_condition == 1 ? "" : "s") + " per condition that are not analysed";
}

class Builder {
 public:
  Builder(const StudyDatabaseAnalysis& a, ReportOptions options) : a_(a) { doc_.options = options; }

  ReportDocument build() {
    doc_.title = a_.protocol.title.empty() ? a_.study.name : a_.protocol.title;
    doc_.subtitle = "Study “" + a_.study.name + "”: results from its database";
    if (a_.completeness.partial())
      paragraph({words("Partial study: it holds " + a_.completeness.describe() +
                       ", merged from only some of its parts. The results below are of these "
                       "participants alone, not of the study; merge the missing parts in "
                       "(handlab-cli merge --update) and make the report again.")});
    protocol();
    participants();
    data_quality();
    completion_time();
    timeouts();
    participant_variables();
    questionnaire();
    return std::move(doc_);
  }

 private:
  void heading(const std::string& text, int level = 1) {
    ReportBlock b;
    b.kind = ReportBlock::Kind::kHeading;
    b.level = level;
    b.text = {words(text)};
    doc_.blocks.push_back(std::move(b));
  }
  void paragraph(ReportLine line) {
    ReportBlock b;
    b.kind = ReportBlock::Kind::kParagraph;
    b.text = std::move(line);
    doc_.blocks.push_back(std::move(b));
  }
  void table(ReportTable t) {
    ReportBlock b;
    b.kind = ReportBlock::Kind::kTable;
    t.caption = "Table " + std::to_string(++tables_) + ". " + t.caption;
    b.table = std::move(t);
    doc_.blocks.push_back(std::move(b));
  }
  void figure(FigureKind kind, const std::string& id, const std::string& caption) {
    ReportBlock b;
    b.kind = ReportBlock::Kind::kFigure;
    b.figure = {kind, id, "Figure " + std::to_string(++figures_) + ". " + caption};
    doc_.blocks.push_back(std::move(b));
  }
  std::vector<std::string> factor_names() const {
    std::vector<std::string> names;
    for (const std::string& n : a_.study.factors) names.push_back(display(n));
    return names;
  }
  std::string error_bars() const {
    return doc_.options.error_bars == ErrorBars::kWithinParticipant
               ? "within-participant standard error (Cousineau–Morey: each participant's "
                 "means moved to the grand mean, SE times √(C/(C−1)) over the C cells plotted)"
               : "standard error of the participants' means";
  }

  void protocol() {
    const Protocol& p = a_.protocol;
    heading("Study and protocol");
    std::vector<std::string> factors;
    std::string sizes;
    for (const Factor& f : p.factors) {
      std::vector<std::string> levels;
      for (const Level& l : f.levels)  // a label that is not its method says which it runs
        levels.push_back(display(l.name) + (l.method && describe(*l.method) != l.name
                                                ? ": " + describe(*l.method)
                                                : std::string()));
      factors.push_back(display(f.name) + " (" + join(levels, ", ") + ")");
      sizes += (sizes.empty() ? "" : " × ") + std::to_string(f.levels.size());
    }
    factors.push_back("Repetition (1–" + std::to_string(p.blocks) + ")");
    sizes += " × " + std::to_string(p.blocks);
    const char* order = p.counterbalancing == Counterbalancing::kRandomizedPerBlock
                            ? "drawn at random for each participant and block"
                        : p.counterbalancing == Counterbalancing::kLatinSquare
                            ? "the participant's row of a balanced Latin square in every block"
                            : "fixed, in the protocol's order";
    const std::size_t conditions = p.conditions().size();
    std::string groups;
    for (const BetweenFactor& f : p.between) {
      std::vector<std::string> levels;
      for (const BetweenLevel& l : f.levels) levels.push_back(display(l.name));
      groups += std::string(groups.empty() ? ", with " : " × ") + display(f.name) + " (" +
                join(levels, ", ") + "; " + assignment_rule(f, display(f.field)) + ")";
    }
    paragraph({words("Protocol “" + p.name + "” (SHA-256 " + a_.study.protocol_sha256 + "): a " +
                     sizes + " within-participants design, " + join_all(factors, " × ") + groups +
                     (groups.empty() ? "" : " between participants") + ". Each participant ran " +
                     std::to_string(p.blocks) + " blocks of the " + std::to_string(conditions) +
                     " conditions, the order within a block " + order + practice_clause(p) +
                     ". A trial ends when the cube rests in zone B for " + fixed(p.rest_time_s, 1) +
                     " s, or at the " + fixed(p.timeout_s, 0) + " s timeout. Simulated hand: " +
                     fixed(100 * p.simulated_hand_length, 1) + " cm long.")});
    if (p.items.empty() || p.questionnaire_timing == QuestionnaireTiming::kNever) {
      paragraph({words("The protocol asks no questionnaire.")});
      return;
    }
    ReportTable t;
    t.caption = "Questionnaire items (" + std::to_string(p.scale_points) + "-point scale, asked " +
                p.questionnaire_schedule() + ").";
    t.header = {"Item", "Question", "Anchors (1 to " + std::to_string(p.scale_points) + ")"};
    for (const QuestionnaireItem& item : p.items)
      t.rows.push_back(
          {{words(display(item.id))}, {words(item.text)}, {words(join_all(item.anchors, " · "))}});
    table(std::move(t));
  }

  void participants() {
    const ParticipantSummary& s = a_.participants;
    heading("Participants");
    ReportLine line = {count(s.enrolled, "/participants/enrolled"),
                       words(" participants enrolled")};
    if (s.simulated > 0)
      append(line, {words(" ("), count(s.simulated, "/participants/simulated"),
                    words(" of them simulated by the participant model, marked as such)")});
    if (a_.completion_time)
      append(line, {words("; "), count(s.analysed, "/participants/analysed"), words(" analysed.")});
    else
      append(line, {words("; none analysed yet.")});
    if (s.age_n > 0)
      append(line, {words(" Age: M = "), number(s.age_mean, 1, "/participants/age_mean"),
                    words(", SD = "), number(s.age_sd, 2, "/participants/age_sd"),
                    words(", range "), number(s.age_min, 0, "/participants/age_min"), words("–"),
                    number(s.age_max, 0, "/participants/age_max"), words(".")});
    auto counts = [&](const char* what, const char* key,
                      const std::vector<std::pair<std::string, int>>& list) {
      append(line, {words(std::string(" ") + what + ": ")});
      for (std::size_t i = 0; i < list.size(); ++i) {
        if (i) append(line, {words(", ")});
        append(line,
               {count(list[i].second, std::string("/participants/") + key + "/" + list[i].first),
                words(" " + list[i].first)});
      }
      append(line, {words(".")});
    };
    if (s.enrolled > 0) {
      counts("Sex", "sex", s.sex);
      counts("Handedness", "handedness", s.handedness);
      append(line,
             {words(" Hand length: "), number(s.hand_cm_min, 1, "/participants/hand_length_cm_min"),
              words("–"), number(s.hand_cm_max, 1, "/participants/hand_length_cm_max"),
              words(" cm (M = "), number(s.hand_cm_mean, 2, "/participants/hand_length_cm_mean"),
              words(", SD = "), number(s.hand_cm_sd, 2, "/participants/hand_length_cm_sd"),
              words(").")});
      counts("VR experience", "vr_experience", s.vr_experience);
      for (const auto& [factor, levels] : s.groups)
        counts(("Group " + display(factor)).c_str(), ("groups/" + factor).c_str(), levels);
    }
    paragraph(std::move(line));
  }

  void data_quality() {
    const DataQuality& q = a_.quality;
    heading("Data quality");
    ReportTable t;
    t.caption = "Scheduled trials (practice not included) and what became of them.";
    t.header = {"Measure", "Count"};
    auto row = [&](const std::string& what, long long n, const std::string& key) {
      t.rows.push_back({{words(what)}, {count(n, "/data_quality/" + key)}});
    };
    row("Trials scheduled", q.planned, "planned");
    row("Completed (cube placed in B)", q.completed, "completed");
    row("Timed out", q.timeouts, "timeouts");
    row("Skipped by the experimenter", q.skipped, "skipped");
    row("Not run yet", q.not_run, "not_run");
    row("Attempts aborted (interrupted, run again)", q.attempts_aborted, "attempts_aborted");
    row("Attempts redone by the experimenter", q.attempts_redone, "attempts_redone");
    row("Practice trials run", q.practice_run, "practice_run");
    row("Frames stored", q.frames, "frames");
    table(std::move(t));
    ReportTable per;
    per.caption = "Scheduled trials per condition: each counted by its last attempt that ended.";
    per.header = {"Condition", "Scheduled", "Completed", "Timed out", "Skipped", "Not run"};
    for (std::size_t i = 0; i < q.by_condition.size(); ++i) {
      const ConditionOutcome& c = q.by_condition[i];
      const std::string key = "/data_quality/by_condition/" + std::to_string(i) + "/";
      std::string label = display(c.condition);  // levels joined by '-'
      std::replace(label.begin(), label.end(), '-', ' ');
      per.rows.push_back({{words(label)},
                          {count(c.planned, key + "planned")},
                          {count(c.completed, key + "completed")},
                          {count(c.timeouts, key + "timeouts")},
                          {count(c.skipped, key + "skipped")},
                          {count(c.not_run, key + "not_run")}});
    }
    table(std::move(per));
    if (q.left_out.empty()) {
      paragraph({words("No participant was left out of an analysis.")});
    } else {
      std::vector<std::string> who;
      for (const auto& [id, why] : q.left_out) who.push_back(id + " (" + why + ")");
      paragraph({words("Left out of an analysis: " + join_all(who, "; ") + ".")});
    }
  }

  void completion_time() {
    heading("Completion time");
    if (!a_.completion_time) {
      paragraph({words("Not computed: " + a_.completion_time_not_computed + ".")});
      if (a_.time_by_condition.empty()) return;
    }
    // Descriptives per condition.
    ReportTable d;
    d.caption = "Completion time (s) per condition: participants' means.";
    for (const std::string& f : a_.study.factors) d.header.push_back(display(f));
    for (const char* h : {"n", "M", "SD", "SE", "SE within", "Mdn"}) d.header.push_back(h);
    for (std::size_t i = 0; i < a_.time_by_condition.size(); ++i) {
      const CellSummary& c = a_.time_by_condition[i];
      const std::string key = "/condition_descriptives/" + std::to_string(i) + "/";
      std::vector<ReportLine> row;
      for (const std::string& l : c.levels) row.push_back({words(display(l))});
      row.push_back({count(c.n, key + "n")});
      row.push_back({number(c.mean, 2, key + "mean")});
      row.push_back({number(c.sd, 2, key + "sd")});
      row.push_back({number(c.se, 2, key + "se")});
      row.push_back({number(c.se_within, 2, key + "se_within")});
      row.push_back({number(c.median, 2, key + "median")});
      d.rows.push_back(std::move(row));
    }
    d.note = "SE within: Cousineau–Morey within-participant standard error.";
    table(std::move(d));
    if (!a_.completion_time) return;
    const analysis::AnalysisReport& r = *a_.completion_time;
    planned_comparisons(r);
    figure(FigureKind::kTimeByCondition, "time-by-condition",
           "Mean (± " + error_bars() +
               ") time to complete the task per condition. Brackets: the planned comparisons "
               "(conditions that differ in one factor), Tukey-adjusted; * p < .05, ** p < .01, "
               "*** p < .001, n.s. not significant.");

    // The ANOVA, APA style.
    heading("Repeated-measures ANOVA", 2);
    ReportTable t = anova_table(r, "/completion_time");
    t.caption = "Repeated-measures ANOVA of completion time (type III sums of squares), N = " +
                std::to_string(r.n_subjects) + ".";
    table(std::move(t));
    for (std::size_t i = 0; i < r.anova.effects.size(); ++i)
      if (const stats::AnovaEffect& e = r.anova.effects[i]; anova_significant(e))
        paragraph(anova_sentence("/completion_time/anova/" + std::to_string(i) + "/", e,
                                 sphericity_corrected(e), "completion time"));
    figure(FigureKind::kTimeByRepetition, "time-by-repetition",
           "Mean (± " + error_bars() + ") time to complete the task per repetition, by " +
               join(factor_names(), " (left) and by ") + " (right).");
    posthoc(r);
  }

  // The completion time the two other ways: the timed-out trials left out, and success as an
  // outcome of its own (timeout_analyses.h).
  void timeouts() {
    if (!a_.completion_time) return;
    heading("Timed-out trials", 2);
    const DataQuality& q = a_.quality;
    paragraph(
        {words("A trial not done within the protocol's limit of "),
         number(a_.protocol.timeout_s, 0, "/study/timeout_s"), words(" s ends as a timeout ("),
         count(q.timeouts, "/data_quality/timeouts"), words(" of "),
         count(q.planned, "/data_quality/planned"),
         words(" scheduled trials). The analysis above counts a timed-out trial at that limit, "
               "a time censored there; below, the timed-out trials are left out, and success "
               "is analysed as an outcome of its own. Where no trial times out the three "
               "agree.")});
    const OutcomeAnalysis& without = a_.time_without_timeouts;
    if (without.result) {
      ReportTable t = anova_table(*without.result, "/completion_time_without_timeouts");
      t.caption =
          "Repeated-measures ANOVA of completion time, the timed-out trials left out, N = " +
          std::to_string(without.result->n_subjects) +
          " (the participants with a completed trial in every condition and repetition).";
      table(std::move(t));
    } else {
      paragraph({words("Completion time without the timed-out trials not computed: " +
                       without.not_computed + ".")});
    }
    ReportTable rates;
    rates.caption = "Success per condition: the scheduled trials completed.";
    rates.header = {"Condition", "Completed", "Timed out", "Completed of scheduled"};
    for (std::size_t i = 0; i < q.by_condition.size(); ++i) {
      const ConditionOutcome& c = q.by_condition[i];
      const std::string key = "/data_quality/by_condition/" + std::to_string(i) + "/";
      std::string label = display(c.condition);
      std::replace(label.begin(), label.end(), '-', ' ');
      rates.rows.push_back(
          {{words(label)},
           {count(c.completed, key + "completed")},
           {count(c.timeouts, key + "timeouts")},
           {bounded(double(c.completed) / std::max(1, c.planned), 2, key + "success_rate")}});
    }
    table(std::move(rates));
    if (!a_.success.result) {
      paragraph({words("Success rates not compared: " + a_.success.not_computed + ".")});
      return;
    }
    const analysis::AnalysisReport& s = *a_.success.result;
    ReportTable f = friedman_table(s, "/success");
    f.caption = "Friedman test of each participant's share of completed trials over the " +
                std::to_string(a_.protocol.conditions().size()) + " conditions.";
    table(std::move(f));
    for (std::size_t i = 0; i < s.friedman.size(); ++i)
      paragraph(friedman_sentence(s, i, "/success", "the shares of completed trials"));
    ReportTable w = wilcoxon_table(s, "/success");
    w.caption =
        "Wilcoxon signed-rank tests of the shares of completed trials between every pair "
        "of conditions.";
    table(std::move(w));
  }

  void planned_comparisons(const analysis::AnalysisReport& r) {
    std::string effect;
    for (const std::string& f : a_.study.factors) effect += (effect.empty() ? "" : ":") + f;
    for (std::size_t k = 0, index = 0; k < r.posthoc.size(); ++k) {
      for (const stats::PairwiseContrast& c : r.posthoc[k].contrasts) {
        const std::size_t i = index++;
        if (c.effect != effect || !c.by.empty()) continue;
        int differ = 0;
        for (std::size_t f = 0; f < c.first.size(); ++f)
          differ += c.first[f].second != c.second[f].second ? 1 : 0;
        if (differ != 1) continue;
        PlannedComparison p;
        for (const auto& [f, l] : c.first) p.first.push_back(l);
        for (const auto& [f, l] : c.second) p.second.push_back(l);
        p.p_tukey = c.p_tukey;
        p.source = "/completion_time/posthoc/" + std::to_string(i) + "/p_tukey";
        doc_.planned.push_back(p);
      }
    }
  }

  // Post hoc tables: the protocol's factors' interaction (the paper's four conditions against
  // each other) always, and every other effect the ANOVA found significant.
  void posthoc(const analysis::AnalysisReport& r) {
    std::string planned_effect;
    for (const std::string& f : a_.study.factors)
      planned_effect += (planned_effect.empty() ? "" : ":") + f;
    heading("Post hoc comparisons", 2);
    std::size_t index = 0;
    for (const stats::PosthocResult& ph : r.posthoc) {
      const std::size_t first = index;
      index += ph.contrasts.size();
      if (ph.contrasts.empty()) continue;
      const std::string& effect = ph.contrasts.front().effect;
      bool significant = false;
      for (const stats::AnovaEffect& e : r.anova.effects)
        if (e.effect == effect) significant = anova_significant(e);
      if (effect != planned_effect && !significant) continue;
      ReportTable t;
      t.caption = "Pairwise comparisons of " + effect_name(effect) +
                  ": paired t tests on participants' means, p adjusted by Tukey's method.";
      t.header = {"Contrast", "Difference (s)", "SE", "t", "df", "p (Tukey)"};
      for (std::size_t j = 0; j < ph.contrasts.size(); ++j) {
        const stats::PairwiseContrast& c = ph.contrasts[j];
        const std::string key = "/completion_time/posthoc/" + std::to_string(first + j) + "/";
        t.rows.push_back({{words(pair_levels(c.first) + " − " + pair_levels(c.second))},
                          {number(c.estimate, 2, key + "estimate")},
                          {number(c.se, 2, key + "se")},
                          {number(c.t, 2, key + "t")},
                          {number(c.df, 0, key + "df")},
                          p_cell(c.p_tukey, key + "p_tukey")});
      }
      table(std::move(t));
      // Sentences: every planned comparison, and every significant one.
      for (std::size_t j = 0; j < ph.contrasts.size(); ++j) {
        const stats::PairwiseContrast& c = ph.contrasts[j];
        const std::string key = "/completion_time/posthoc/" + std::to_string(first + j) + "/";
        bool planned = false;
        if (effect == planned_effect) {
          int differ = 0;
          for (std::size_t f = 0; f < c.first.size(); ++f)
            differ += c.first[f].second != c.second[f].second ? 1 : 0;
          planned = differ == 1;
        }
        if (!planned && !(c.p_tukey < kAlpha)) continue;
        const bool faster = c.estimate < 0;
        ReportLine line = {words(std::string(planned ? "Planned comparison: " : "") +
                                 pair_levels(c.first) + " against " + pair_levels(c.second) +
                                 ": ")};
        if (c.p_tukey < kAlpha)
          append(line, {words(std::string("the task took ") + (faster ? "less" : "more") +
                              " time in " + pair_levels(c.first) + " (difference ")});
        else
          append(line, {words("no significant difference (difference ")});
        append(line, {number(c.estimate, 2, key + "estimate"), words(" s), t("),
                      number(c.df, 0, key + "df"), words(") = "), number(c.t, 2, key + "t"),
                      words(", ")});
        append(line, p_line(c.p_tukey, key + "p_tukey", "p"));
        append(line, {words(", Tukey-adjusted.")});
        paragraph(std::move(line));
      }
    }
  }

  void participant_variables() {
    if (a_.participant_variables.empty()) return;
    heading("Participant variables");
    paragraph(
        {words("As in the paper, further ANOVAs of completion time over " + join(factor_names()) +
               " (repetitions averaged) with one participant variable each: age and hand "
               "length as centred covariates, VR experience as a between-participants "
               "factor. The table shows the effects that involve the variable.")});
    ReportTable t;
    t.caption = "ANOVAs with one participant variable: the effects that involve it.";
    t.header = {"Variable", "Effect", "df", "F", "p", "η²G"};
    std::vector<ReportLine> sentences;
    for (std::size_t v = 0; v < a_.participant_variables.size(); ++v) {
      const ParticipantVariableAnalysis& pv = a_.participant_variables[v];
      if (!pv.result) {
        t.rows.push_back({{words(display(pv.variable))},
                          {words("not computed: " + pv.not_computed)},
                          {},
                          {},
                          {},
                          {}});
        continue;
      }
      for (std::size_t i = 0; i < pv.result->anova.effects.size(); ++i) {
        const stats::AnovaEffect& e = pv.result->anova.effects[i];
        if (e.effect.find(pv.variable) == std::string::npos) continue;
        const std::string key = "/participant_variables/" + std::to_string(v) + "/analysis/anova/" +
                                std::to_string(i) + "/";
        t.rows.push_back({{words(display(pv.variable))},
                          {words(effect_name(e.effect))},
                          {number(e.df_num, 0, key + "df_num"), words(", "),
                           number(e.df_den, 0, key + "df_den")},
                          {number(e.f, 2, key + "F")},
                          p_cell(e.p, key + "p"),
                          {bounded(e.ges, 3, key + "ges")}});
        if (e.p < kAlpha) sentences.push_back(anova_sentence(key, e, false, "completion time"));
      }
    }
    table(std::move(t));
    if (sentences.empty())
      paragraph({words("No effect involving a participant variable was significant.")});
    for (ReportLine& s : sentences) paragraph(std::move(s));
    if (!a_.time_by_hand_length.empty())
      figure(FigureKind::kTimeByHandLength, "time-by-hand-length",
             "Participants' mean time to complete the task against their hand length, by " +
                 join(factor_names(), " (left) and by ") +
                 " (right), with a least-squares line per level.");
  }

  void questionnaire() {
    heading("Questionnaire");
    if (!a_.questionnaire) {
      paragraph({words("Not computed: " + a_.questionnaire_not_computed + ".")});
      return;
    }
    const analysis::AnalysisReport& q = *a_.questionnaire;
    ReportTable f = friedman_table(q, "/questionnaire");
    f.caption = "Friedman tests over the " + std::to_string(a_.protocol.conditions().size()) +
                " conditions, per item.";
    table(std::move(f));
    for (std::size_t i = 0; i < q.friedman.size(); ++i)
      paragraph(friedman_sentence(q, i, "/questionnaire", "the scores"));
    ReportTable w = wilcoxon_table(q, "/questionnaire");
    w.caption = "Wilcoxon signed-rank tests between every pair of conditions, per item.";
    table(std::move(w));
    figure(FigureKind::kItems, "questionnaire",
           "Median (± range) self-reported scores per item and condition.");
  }

  const StudyDatabaseAnalysis& a_;
  ReportDocument doc_;
  int tables_ = 0, figures_ = 0;
};

}  // namespace

bool ReportTable::numeric(std::size_t column) const {
  for (const auto& row : rows)
    if (column < row.size())
      for (const ReportText& t : row[column])
        if (!t.source.empty()) return true;
  return false;
}

std::string plain(const ReportLine& line) {
  std::string out;
  for (const ReportText& t : line) out += t.text;
  return out;
}

ReportDocument build_report(const StudyDatabaseAnalysis& analysis, ReportOptions options) {
  return Builder(analysis, options).build();
}

}  // namespace handlab::studies
