#include "studies/analysis/study_series.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "analysis/stats/descriptives.h"
#include "analysis/stats/effect_size.h"
#include "core/util/data_files.h"
#include "core/util/json_value.h"
#include "core/util/json_writer.h"

namespace handlab::studies {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

[[noreturn]] void refuse(const std::string& path, const std::string& why) {
  throw std::runtime_error(path + ": " + why);
}

double number_or_nan(const util::JsonValue& test, const char* key, const std::string& path) {
  const util::JsonValue* v = test.find(key);
  if (!v || v->is_null()) return kNaN;
  if (!v->is_number()) refuse(path, std::string("a test's \"") + key + "\" is not a number");
  return v->as_number();
}

// Median, smallest and largest of the finite values.
void describe(const std::vector<double>& values, double& median, double& min, double& max) {
  std::vector<double> finite;
  for (double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  std::sort(finite.begin(), finite.end());
  median = finite.empty() ? kNaN : stats::quantile_type7(finite, 0.5);
  min = finite.empty() ? kNaN : finite.front();
  max = finite.empty() ? kNaN : finite.back();
}

// The effect size a test's statistic gives (effect_size.h), NaN for the others.
std::string effect_name(const std::string& statistic) {
  return statistic == "F" ? "pes" : statistic == "t" ? "dz" : "";
}

// A t's people: as given, else those of a paired test (df + 1).
double people(const std::vector<double>& df, int participants) {
  return participants > 0 ? double(participants) : df[0] + 1.0;
}

double effect_of(const std::string& statistic, double value, const std::vector<double>& df,
                 int participants) {
  if (statistic == "F" && df.size() == 2) return stats::partial_eta_squared(value, df[0], df[1]);
  if (statistic == "t" && df.size() == 1) return stats::paired_dz(value, people(df, participants));
  return kNaN;
}

stats::EffectInterval published_interval(const PublishedTest& p, int participants) {
  if (!std::isfinite(p.value)) return {kNaN, kNaN};
  if (p.statistic == "F" && p.df.size() == 2)
    return stats::partial_eta_squared_interval(p.value, p.df[0], p.df[1]);
  if (p.statistic == "t" && p.df.size() == 1)
    return stats::paired_dz_interval(p.value, p.df[0], people(p.df, participants));
  return {kNaN, kNaN};
}

// The median and the 2.5 and 97.5 % quantiles of the finite values.
void describe_spread(const std::vector<double>& values, double& median, double& low, double& high) {
  std::vector<double> finite;
  for (double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  std::sort(finite.begin(), finite.end());
  median = finite.empty() ? kNaN : stats::quantile_type7(finite, 0.5);
  low = finite.empty() ? kNaN : stats::quantile_type7(finite, 0.025);
  high = finite.empty() ? kNaN : stats::quantile_type7(finite, 0.975);
}

std::string fixed(double x, int decimals) {
  if (!std::isfinite(x)) return "–";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, x);
  return text;
}

// p as a results section prints it: ".008", "<.001".
std::string p_text(double p) {
  if (!std::isfinite(p)) return "–";
  if (p < 0.001) return "<.001";
  std::string text = fixed(p, 3);
  return text.rfind("0.", 0) == 0 ? text.substr(1) : text;
}

std::string statistic_text(const std::string& statistic, double value) {
  return fixed(value, statistic == "V" ? 1 : 2);
}

std::string percent(int part, int whole) {
  return whole > 0 ? fixed(100.0 * part / whole, 0) + " %" : "–";
}

std::string capitalised(std::string text) {
  if (!text.empty() && text[0] >= 'a' && text[0] <= 'z') text[0] = char(text[0] - 'a' + 'A');
  return text;
}

// A table's header: its first column, the columns before the studies, one per study, and the
// columns after them.
void write_header(const std::string& first, const std::vector<std::string>& extra,
                  std::size_t studies, const std::vector<std::string>& tail, std::ostream& out) {
  out << "| " << first;
  for (const std::string& e : extra) out << " | " << e;
  for (std::size_t k = 0; k < studies; ++k) out << " | " << k + 1;
  for (const std::string& t : tail) out << " | " << t;
  out << " |\n|---";
  for (std::size_t c = 0; c < extra.size() + studies + tail.size(); ++c) out << "|---";
  out << "|\n";
}

// The share of a study's trials that dropped the cube, and that grasped it again with no drop.
std::string loss_text(const LossCount& c) {
  return c.trials > 0
             ? percent(c.dropped, c.trials) + " (" + percent(c.grasped_again, c.trials) + ")"
             : "–";
}

// Per condition, then per repetition: each study's losses and the pooled studies'.
void write_losses(const StudySeries& s, std::ostream& out) {
  out << "\nTrials that lost the cube: the share that dropped it at least once (it came to rest "
         "out of B) and, in parentheses, that grasped it again with no drop (the pinch broken, "
         "the cube caught or picked up before it rested)\n\n";
  write_header("condition, repetition", {}, s.studies.size(), {"pooled"}, out);
  std::size_t repetitions = 0;
  for (const SeriesStudy& study : s.studies)
    repetitions = std::max(repetitions, study.losses.by_repetition.size());
  auto row = [&](const std::string& label, auto cell) {
    LossCount pooled;
    out << "| " << label;
    for (const SeriesStudy& study : s.studies) {
      const LossCount* c = cell(study.losses);
      out << " | " << (c ? loss_text(*c) : "–");
      if (!c) continue;
      pooled.trials += c->trials;
      pooled.dropped += c->dropped;
      pooled.grasped_again += c->grasped_again;
    }
    out << " | " << loss_text(pooled) << " |\n";
  };
  for (std::size_t c = 0; c < s.conditions.size(); ++c)
    row(s.conditions[c], [&](const CubeLosses& l) {
      return c < l.by_condition.size() ? &l.by_condition[c] : nullptr;
    });
  for (std::size_t r = 0; r < repetitions; ++r)
    row("repetition " + std::to_string(r + 1), [&](const CubeLosses& l) {
      return r < l.by_repetition.size() ? &l.by_repetition[r] : nullptr;
    });
}

// One test's row: the published value, the statistic (p) per study, and the series' summary.
void write_test_row(const SeriesTest& t, bool published, std::size_t n, std::ostream& out) {
  out << "| " << t.name << " | " << t.statistic;
  if (published) {
    out << " | ";
    if (t.published) {
      const PublishedTest& p = *t.published;
      if (std::isfinite(p.value)) out << statistic_text(p.statistic, p.value) << " ";
      if (std::isfinite(p.p)) out << "(" << (p.p_below ? "<" : "") << p_text(p.p) << ")";
    }
  }
  for (std::size_t k = 0; k < n; ++k)
    out << " | "
        << (std::isfinite(t.p[k]) || std::isfinite(t.value[k])
                ? statistic_text(t.statistic, t.value[k]) + " (" + p_text(t.p[k]) + ")"
                : std::string("–"));
  out << " | " << statistic_text(t.statistic, t.median) << " | "
      << statistic_text(t.statistic, t.min) << " to " << statistic_text(t.statistic, t.max) << " | "
      << p_text(t.p_median) << " | " << t.rejected << " of " << t.studies;
  if (published)
    out << " | "
        << (t.below_published >= 0
                ? std::to_string(t.below_published) + " of " + std::to_string(t.studies)
                : std::string());
  out << " |\n";
}

// The effect sizes of the F and t tests beside the published one's 95 % interval: agreement
// judged by how large an effect is, not by how many studies reached p < alpha.
void write_effect_sizes(const StudySeries& s, std::ostream& out) {
  const bool published = s.published.has_value();
  out << "\nEffect sizes: partial eta squared (pes) of each F test, d_z (t / sqrt(n), n the "
         "participants) of "
         "each t test; the median and the 2.5-97.5 % range over the studies"
      << (published ? "; beside the published value with its 95 % interval from the noncentral "
                      "F or t, and how many studies' effects fall inside it"
                    : "")
      << "\n\n| test | effect |" << (published ? " published (95 % CI) |" : "")
      << " median | 2.5-97.5 % |" << (published ? " within the published CI |" : "")
      << "\n|---|---|" << (published ? "---|" : "") << "---|---|" << (published ? "---|" : "")
      << "\n";
  for (const SeriesTest& t : s.tests) {
    if (t.effect.empty()) continue;
    out << "| " << t.name << " | " << t.effect << " | ";
    if (published)
      out << (std::isfinite(t.published_effect)
                  ? fixed(t.published_effect, 2) + " (" + fixed(t.published_low, 2) + " to " +
                        fixed(t.published_high, 2) + ")"
                  : std::string("–"))
          << " | ";
    out << fixed(t.effect_median, 2) << " | " << fixed(t.effect_low, 2) << " to "
        << fixed(t.effect_high, 2) << " |";
    if (published)
      out << " "
          << (t.within_published >= 0
                  ? std::to_string(t.within_published) + " of " + std::to_string(t.studies)
                  : std::string("–"))
          << " |";
    out << "\n";
  }
}

}  // namespace

PublishedStudy read_published_study(const std::string& named) {
  const std::string path = util::find_data_file(named);
  std::ifstream in(path, std::ios::binary);
  if (!in) refuse(path, "cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  util::JsonValue root;
  try {
    root = util::JsonValue::parse(text.str());
  } catch (const util::JsonError& e) {
    refuse(path, e.what());
  }
  try {
    if (root["format"].as_string() != "handlab-published-results")
      refuse(path, "\"format\" must be \"handlab-published-results\"");
    if (root["version"].as_number() != 1) refuse(path, "\"version\" must be 1");
    PublishedStudy study;
    study.protocol = root["protocol"].as_string();
    study.source = root["source"].as_string();
    study.participants = int(root["participants"].as_number());
    std::set<std::string> names;
    for (const util::JsonValue& t : root["tests"].as_array()) {
      PublishedTest test;
      test.name = t["test"].as_string();
      test.statistic = t["statistic"].as_string();
      if (!names.insert(test.name).second) refuse(path, "the test '" + test.name + "' twice");
      if (test.statistic != "F" && test.statistic != "t" && test.statistic != "chi2" &&
          test.statistic != "V")
        refuse(path, "'" + test.name + "': statistic must be F, t, chi2 or V");
      test.value = number_or_nan(t, "value", path);
      if (const util::JsonValue* df = t.find("df"))
        for (const util::JsonValue& d : df->as_array()) test.df.push_back(d.as_number());
      test.p = number_or_nan(t, "p", path);
      const double below = number_or_nan(t, "p_below", path);
      if (std::isfinite(below)) {
        if (std::isfinite(test.p)) refuse(path, "'" + test.name + "': give p or p_below, not both");
        test.p = below;
        test.p_below = true;
      }
      study.tests.push_back(std::move(test));
    }
    return study;
  } catch (const util::JsonError& e) {
    refuse(path, e.what());
  }
}

StudySeries summarize_series(const std::vector<std::string>& paths, const SeriesOptions& options) {
  if (paths.empty()) throw std::runtime_error("no study to summarise");
  StudySeries series;
  series.alpha = options.alpha;
  std::vector<StudyTests> found;
  std::set<std::filesystem::path> seen;
  for (const std::string& path : paths) {
    std::error_code error;
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(path, error);
    if (!seen.insert(error ? std::filesystem::path(path) : canonical).second)
      refuse(path, "given twice: each study counts once");
    const StudyDatabaseAnalysis a = analyze_study_database(path);
    if (series.studies.empty()) {
      series.protocol = a.study.name;
      series.protocol_sha256 = a.study.protocol_sha256;
      for (const ConditionOutcome& c : a.quality.by_condition)
        series.conditions.push_back(c.condition);
    } else if (a.study.protocol_sha256 != series.protocol_sha256) {
      refuse(path, "a study of another protocol than " + paths.front() + " (" + a.study.name +
                       ", sha256 " + a.study.protocol_sha256.substr(0, 12) + " against " +
                       series.protocol_sha256.substr(0, 12) + ")");
    }
    SeriesStudy study;
    study.path = path;
    study.participants = a.completion_time ? a.completion_time->n_subjects : 0;
    study.conditions = a.quality.by_condition;
    study.losses = a.quality.losses;
    found.push_back(study_tests(a, options.correction, options.alpha));
    study.warning = found.back().warning;
    series.studies.push_back(std::move(study));
  }
  if (options.published && options.published->protocol != series.protocol)
    throw std::runtime_error("the published results are of the protocol '" +
                             options.published->protocol + "', the studies of '" + series.protocol +
                             "'");
  series.published = options.published;

  // Every test any study made, in the order the first that made it names it.
  std::vector<std::string> names;
  for (const StudyTests& f : found)
    for (const StudyTest& t : f.tests)
      if (std::find(names.begin(), names.end(), t.name) == names.end()) names.push_back(t.name);
  if (!options.only.empty()) {
    for (const std::string& name : options.only)
      if (std::find(names.begin(), names.end(), name) == names.end())
        throw std::runtime_error("no study made the test '" + name + "'");
    names = options.only;
  }
  const std::size_t n = paths.size();
  for (const std::string& name : names) {
    SeriesTest s;
    s.name = name;
    s.value.assign(n, kNaN);
    s.p.assign(n, kNaN);
    s.effect_value.assign(n, kNaN);
    for (std::size_t k = 0; k < n; ++k)
      for (const StudyTest& t : found[k].tests) {
        if (t.name != name) continue;
        s.statistic = t.statistic;
        s.group = t.group;
        s.value[k] = t.value;
        s.p[k] = t.p;
        s.effect = effect_name(t.statistic);
        s.effect_value[k] = effect_of(t.statistic, t.value, t.df, t.participants);
        ++s.studies;
        s.rejected += t.p < options.alpha ? 1 : 0;
      }
    describe(s.value, s.median, s.min, s.max);
    describe_spread(s.effect_value, s.effect_median, s.effect_low, s.effect_high);
    double ignored_min, ignored_max;
    describe(s.p, s.p_median, ignored_min, ignored_max);
    if (options.published)
      for (const PublishedTest& p : options.published->tests)
        if (p.name == name) s.published = p;
    if (s.published && std::isfinite(s.published->value)) {
      s.below_published = 0;
      for (double v : s.value) s.below_published += v < s.published->value ? 1 : 0;
    }
    s.published_effect = s.published_low = s.published_high = kNaN;
    if (s.published && s.published->statistic == s.statistic) {
      const int n = options.published->participants;
      const stats::EffectInterval ci = published_interval(*s.published, n);
      s.published_effect = effect_of(s.statistic, s.published->value, s.published->df, n);
      s.published_low = ci.low;
      s.published_high = ci.high;
      if (std::isfinite(ci.low)) {
        s.within_published = 0;
        for (double e : s.effect_value) s.within_published += e >= ci.low && e <= ci.high ? 1 : 0;
      }
    }
    series.tests.push_back(std::move(s));
  }
  if (options.published && options.only.empty())
    for (const PublishedTest& p : options.published->tests)
      if (std::find(names.begin(), names.end(), p.name) == names.end())
        series.published_unmatched.push_back(p.name);
  return series;
}

void write_series_markdown(const StudySeries& s, std::ostream& out) {
  const std::size_t n = s.studies.size();
  out << "Series of " << n << " studies of " << s.protocol << " (protocol sha256 "
      << s.protocol_sha256.substr(0, 12) << "), alpha = " << s.alpha << "\n\n";
  out << "| study | database | participants analysed | note |\n|---|---|---|---|\n";
  for (std::size_t k = 0; k < n; ++k)
    out << "| " << k + 1 << " | " << s.studies[k].path << " | " << s.studies[k].participants
        << " | " << s.studies[k].warning << " |\n";

  auto header = [&](const std::string& first, const std::vector<std::string>& extra,
                    const std::vector<std::string>& tail) {
    write_header(first, extra, n, tail, out);
  };
  out << "\nScheduled trials completed before the timeout\n\n";
  header("condition", {}, {"median", "range"});
  for (std::size_t c = 0; c < s.conditions.size(); ++c) {
    out << "| " << s.conditions[c];
    std::vector<double> rates;
    for (const SeriesStudy& study : s.studies) {
      const ConditionOutcome& o = study.conditions[c];
      out << " | " << percent(o.completed, o.planned);
      if (o.planned > 0) rates.push_back(100.0 * o.completed / o.planned);
    }
    double median, min, max;
    describe(rates, median, min, max);
    out << " | " << fixed(median, 1) << " % | " << fixed(min, 0) << "–" << fixed(max, 0)
        << " % |\n";
  }
  write_losses(s, out);

  out << "\nTests: the statistic (p) per study; p as judged (Greenhouse-Geisser where Mauchly's "
         "test rejects sphericity; Tukey for the cells of "
      << "the factors, Bonferroni for Wilcoxon's). The completion time three ways: a timed-out "
         "trial counted at the trial's limit; the timed-out trials left out (a participant "
         "without a completed trial in some cell left out); and each participant's share of "
         "completed trials per condition, compared as the questionnaire's items are\n";
  const bool published = s.published.has_value();
  std::vector<std::string> extra = {"statistic"};
  if (published)
    extra.push_back("published (N = " + std::to_string(s.published->participants) + ")");
  std::ostringstream alpha;
  alpha << "p < " << s.alpha;
  std::vector<std::string> tail = {"median", "range", "p median", alpha.str()};
  if (published) tail.push_back("below published");
  std::vector<std::string> groups;
  for (const SeriesTest& t : s.tests)
    if (std::find(groups.begin(), groups.end(), t.group) == groups.end()) groups.push_back(t.group);
  for (const std::string& group : groups) {
    out << "\n" << capitalised(group) << "\n\n";
    header("test", extra, tail);
    for (const SeriesTest& t : s.tests)
      if (t.group == group) write_test_row(t, published, n, out);
  }
  write_effect_sizes(s, out);
  if (published) {
    out << "\nPublished: " << s.published->source << "\n";
    if (!s.published_unmatched.empty()) {
      out << "Published tests no study made:";
      for (const std::string& name : s.published_unmatched) out << " '" << name << "'";
      out << "\n";
    }
  }
}

void write_series_json(const StudySeries& s, std::ostream& out) {
  util::JsonWriter json(out);
  json.begin_object().field("protocol", s.protocol).field("protocol_sha256", s.protocol_sha256);
  json.field("alpha", s.alpha);
  json.key("studies").begin_array();
  for (const SeriesStudy& study : s.studies) {
    json.begin_object().field("db", study.path).field("participants", study.participants);
    json.field("warning", study.warning).key("conditions").begin_array();
    for (const ConditionOutcome& c : study.conditions) write_condition_outcome(json, c);
    json.end_array().key("cube_losses");
    write_cube_losses(json, study.losses);
    json.end_object();
  }
  json.end_array();
  json.key("tests").begin_array();
  for (const SeriesTest& t : s.tests) {
    json.begin_object().field("test", t.name).field("statistic", t.statistic);
    json.field("group", t.group);
    json.key("values").begin_array();
    for (double v : t.value) json.value(v);
    json.end_array().key("p").begin_array();
    for (double p : t.p) json.value(p);
    json.end_array();
    json.field("studies", t.studies).field("rejected", t.rejected);
    json.field("median", t.median).field("min", t.min).field("max", t.max);
    json.field("p_median", t.p_median);
    json.field("effect", t.effect).key("effect_values").begin_array();
    for (double e : t.effect_value) json.value(e);
    json.end_array();
    json.field("effect_median", t.effect_median)
        .field("effect_low", t.effect_low)
        .field("effect_high", t.effect_high);
    json.key("published_effect");
    if (std::isfinite(t.published_effect))
      json.begin_object()
          .field("value", t.published_effect)
          .field("low", t.published_low)
          .field("high", t.published_high)
          .end_object();
    else
      json.null();
    json.key("within_published");
    if (t.within_published >= 0)
      json.value(t.within_published);
    else
      json.null();
    json.key("below_published");
    if (t.below_published >= 0)
      json.value(t.below_published);
    else
      json.null();
    json.key("published");
    if (t.published) {
      const PublishedTest& p = *t.published;
      json.begin_object().field("value", p.value).key("df").begin_array();
      for (double d : p.df) json.value(d);
      json.end_array().field("p", p.p).field("p_below", p.p_below).end_object();
    } else {
      json.null();
    }
    json.end_object();
  }
  json.end_array();
  json.key("published");
  if (s.published)
    json.begin_object()
        .field("source", s.published->source)
        .field("participants", s.published->participants)
        .key("unmatched")
        .string_array(s.published_unmatched)
        .end_object();
  else
    json.null();
  json.end_object();
  out << "\n";
}

}  // namespace handlab::studies
