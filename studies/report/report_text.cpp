#include "studies/report/report_text.h"

#include <cmath>
#include <cstdio>

#include "analysis/report/analysis_output.h"

namespace handlab::studies::report_text {

std::string fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "NA";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  std::string s = buffer;
  if (s.find_first_not_of("-0.") == std::string::npos && s.front() == '-') s.erase(0, 1);
  return s;
}

ReportText words(std::string text) {
  return {std::move(text), {}, '='};
}
ReportText number(double v, int decimals, std::string source) {
  return {fixed(v, decimals), std::move(source), '='};
}
// APA: no leading zero for values that cannot exceed 1 (p, eta squared, epsilon, W).
ReportText bounded(double v, int decimals, std::string source) {
  return {analysis::apa_unit(v, decimals), std::move(source), '='};
}
ReportText count(long long n, std::string source) {
  return {std::to_string(n), std::move(source), '='};
}
// "p = .008", "p < .001": the relation word and the bound number.
ReportLine p_line(double p, const std::string& source, const std::string& name) {
  if (!std::isfinite(p)) return {words(name + " = NA")};
  if (p < 0.001) return {words(name + " < "), {".001", source, '<'}};
  const std::string s = fixed(p, 3);
  if (s == "1.000") return {words(name + " > "), {".999", source, '>'}};
  return {words(name + " = "), {s.substr(s.find('.')), source, '='}};
}
// The same in a table cell: "< .001", ".008".
ReportLine p_cell(double p, const std::string& source) {
  ReportLine line = p_line(p, source);
  line.front().text = line.front().text.substr(2);  // drop "p "
  if (line.front().text == "= ") line.erase(line.begin());
  return line;
}
void append(ReportLine& to, const ReportLine& more) {
  to.insert(to.end(), more.begin(), more.end());
}

std::string display(const std::string& name) {
  if (name == "vr_experience") return "VR experience";
  std::string s = name;
  for (char& c : s)
    if (c == '_') c = ' ';
  if (!s.empty() && s[0] >= 'a' && s[0] <= 'z') s[0] = char(s[0] - 'a' + 'A');
  return s;
}
std::string effect_name(const std::string& effect) {
  std::string out;
  std::size_t start = 0;
  while (true) {
    const std::size_t colon = effect.find(':', start);
    out += (out.empty() ? "" : " × ") + display(effect.substr(start, colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  return out;
}
std::string levels_name(const std::vector<std::string>& levels) {
  std::string out;
  for (const std::string& l : levels) out += (out.empty() ? "" : " ") + display(l);
  return out;
}
std::string pair_levels(const std::vector<std::pair<std::string, std::string>>& at) {
  std::vector<std::string> levels;
  for (const auto& [f, l] : at) levels.push_back(l);
  return levels_name(levels);
}
std::string join(const std::vector<std::string>& items, const std::string& last) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i == 0 ? "" : i + 1 == items.size() ? last : ", ") + items[i];
  return out;
}
std::string join_all(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? separator : "") + items[i];
  return out;
}

}  // namespace handlab::studies::report_text
