// A study report as a document: headings, paragraphs, tables and figures in the order of a
// results section, built from a study database's analysis. Every number in it names where it
// comes from (a JSON pointer into `handlab-cli analyze --db DB --json`), so the HTML, the PDF
// and the app show the same values and a test can check each one against the analysis.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "studies/analysis/study_database_analysis.h"

namespace handlab::studies {

// A run of text. A number carries its source: one JSON pointer, or two joined by '*' (a
// product, e.g. a df times its Greenhouse-Geisser epsilon); `relation` says how the shown
// text relates to the value: '=' (the value rounded), '<' or '>' (p < .001, p > .999).
struct ReportText {
  std::string text;
  std::string source;
  char relation = '=';
};
using ReportLine = std::vector<ReportText>;

struct ReportTable {
  std::string caption;
  std::vector<std::string> header;
  std::vector<std::vector<ReportLine>> rows;
  std::string note;
  // A column of numbers (some cell holds one), aligned right; the others are words.
  bool numeric(std::size_t column) const;
};

enum class FigureKind { kTimeByCondition, kTimeByRepetition, kTimeByHandLength, kItems };

struct ReportFigure {
  FigureKind kind = FigureKind::kTimeByCondition;
  std::string id, caption;
};

struct ReportBlock {
  enum class Kind { kHeading, kParagraph, kTable, kFigure };
  Kind kind = Kind::kParagraph;
  int level = 1;    // of a heading: 1 the title's sections, 2 their parts
  ReportLine text;  // a heading's or a paragraph's
  ReportTable table;
  ReportFigure figure;
};

// The planned comparisons of Fig. 3.5: the pairs of conditions that differ in one factor.
struct PlannedComparison {
  std::vector<std::string> first, second;  // levels, one per protocol factor
  double p_tukey = 0;
  std::string source;  // of p_tukey
};

enum class ErrorBars { kStandardError, kWithinParticipant };

struct ReportOptions {
  ErrorBars error_bars = ErrorBars::kStandardError;
};

struct ReportDocument {
  std::string title, subtitle;
  std::vector<ReportBlock> blocks;
  std::vector<PlannedComparison> planned;  // for the figures' brackets
  ReportOptions options;
};

ReportDocument build_report(const StudyDatabaseAnalysis& analysis, ReportOptions options = {});

// The whole line as text.
std::string plain(const ReportLine& line);

// One self-contained HTML file; `figure_svg` gives each figure's SVG markup (empty: the figure
// is left out, its caption kept).
void write_report_html(const ReportDocument& document,
                       const std::function<std::string(const ReportFigure&)>& figure_svg,
                       std::ostream& out);
// A table alone as HTML (the app's Analysis view shows them in a text browser).
std::string report_table_html(const ReportTable& table);

}  // namespace handlab::studies
