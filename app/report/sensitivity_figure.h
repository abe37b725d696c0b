// The sensitivity analysis's figure (`handlab-cli sensitivity --plot`): per output test, each
// parameter's mu* (how much the output moves over the parameter's range) against sigma (how far
// that depends on the other parameters), the five largest named; drawn with QPainter into SVG
// or PNG. Needs a QGuiApplication.
#pragma once

#include <string>

#include "studies/sensitivity/model_sensitivity.h"

namespace handlab::report {

// Writes `path` (.svg or .png); throws std::runtime_error for another extension.
void write_sensitivity_figure(const studies::SensitivityReport& report, const std::string& title,
                              const std::string& path);

}  // namespace handlab::report
