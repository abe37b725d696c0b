// The power curve of `handlab-cli power --plot`: power against the number of participants for
// chosen effects and contrasts, with 95 % intervals and the target power, drawn with QPainter
// into SVG (QSvgGenerator) or PNG (QImage) by one code path. Needs a QGuiApplication.
#pragma once

#include <string>
#include <vector>

#include "analysis/power/power_analysis.h"

namespace handlab::report {

// Writes `path` (.svg or .png); throws std::runtime_error for another extension or a name
// the report lacks.
void write_power_figure(const power::PowerReport& report, const std::vector<std::string>& names,
                        double target, const std::string& title, const std::string& path);

}  // namespace handlab::report
