// A repeated-measures data set in wide form, prepared from a long table as afex's aov_ez
// prepares it: one row per participant, one column per within cell.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/data/long_table.h"

namespace handlab::stats {

struct Factor {
  std::string name;
  std::vector<std::string> levels;  // in order of first appearance in the data
};

struct RmDesignSpec {
  std::string subject;
  std::string dv;
  std::vector<std::string> within;      // factors varying within participants
  std::vector<std::string> between;     // factors constant within participants
  std::vector<std::string> covariates;  // numeric, constant within participants; centred
  std::vector<std::string> observed;    // measured (not manipulated) variables, for ges
};

struct RmData {
  std::vector<Factor> within;
  std::vector<Factor> between;
  std::vector<std::string> covariates;
  std::vector<double> covariate_means;  // the centring means
  std::vector<std::string> observed;
  std::vector<std::string> subjects;  // participants analysed, in order of appearance
  // y(i, c): participant i's value in within cell c (the mean when a cell has several
  // observations). Cells are numbered with the first within factor varying fastest.
  Eigen::MatrixXd y;
  std::vector<std::vector<int>> between_levels;  // [participant][between factor] level index
  Eigen::MatrixXd covariate_values;              // participants x covariates, centred
  std::vector<std::string> dropped_subjects;     // lacking a within cell
  std::vector<std::string> warnings;

  int cells() const { return int(y.cols()); }
  // Level index of each within factor in cell c.
  std::vector<int> cell_levels(int c) const;
  std::string effect_label(const std::vector<int>& within_factors) const;
};

// Validates the design (columns exist, values numeric and finite, factors with two or more
// levels, between factors and covariates constant within participants) and throws
// analysis::DataError naming the column and line of the first problem.
RmData prepare_rm_data(const analysis::LongTable& table, const RmDesignSpec& spec);

}  // namespace handlab::stats
