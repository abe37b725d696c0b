// An analysis report as machine-readable JSON and as APA-style text.
#pragma once

#include <ostream>
#include <string>

#include "analysis/report/study_analysis.h"

namespace handlab::analysis {

void write_json(const AnalysisReport& report, std::ostream& out);
void write_text(const AnalysisReport& report, std::ostream& out);

// APA number styles: p = .008, p < .001; ηp² = .32 (no leading zero for values bounded by 1).
std::string apa_p(double p);
std::string apa_unit(double value, int decimals = 2);
std::string apa_df(double df);

}  // namespace handlab::analysis
