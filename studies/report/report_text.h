// The report's words and numbers: each number with the JSON pointer it comes from, p and the
// bounded statistics in APA style, and the display names of factors, levels and effects.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "studies/report/report_document.h"

namespace handlab::studies::report_text {

inline constexpr double kAlpha = 0.05;

std::string fixed(double v, int decimals);  // "NA" when not finite; never "-0.00"
ReportText words(std::string text);
ReportText number(double v, int decimals, std::string source);
// APA: no leading zero for values that cannot exceed 1 (p, eta squared, epsilon, W).
ReportText bounded(double v, int decimals, std::string source);
ReportText count(long long n, std::string source);
// "p = .008", "p < .001": the relation word and the bound number.
ReportLine p_line(double p, const std::string& source, const std::string& name = "p");
// The same in a table cell: "< .001", ".008".
ReportLine p_cell(double p, const std::string& source);
void append(ReportLine& to, const ReportLine& more);

std::string display(const std::string& name);        // "hand_length" -> "Hand length"
std::string effect_name(const std::string& effect);  // "a:b" -> "A × B"
std::string levels_name(const std::vector<std::string>& levels);
std::string pair_levels(const std::vector<std::pair<std::string, std::string>>& at);
std::string join(const std::vector<std::string>& items, const std::string& last = " and ");
std::string join_all(const std::vector<std::string>& items, const std::string& separator);

}  // namespace handlab::studies::report_text
