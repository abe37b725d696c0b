// Multiple-comparison adjustment as R's p.adjust: NaN p values stay NaN and are not counted.
#pragma once

#include <vector>

namespace handlab::stats {

std::vector<double> p_adjust_bonferroni(const std::vector<double>& p);
std::vector<double> p_adjust_holm(const std::vector<double>& p);

}  // namespace handlab::stats
