// Design matrices of the multivariate linear model behind a repeated-measures ANOVA
// (car::Anova.mlm): the between-participants model X and orthonormal within contrasts.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "analysis/stats/rm_data.h"

namespace handlab::stats {

struct BetweenModel {
  Eigen::MatrixXd x;                    // participants x parameters
  Eigen::MatrixXd xtx_inverse;          // (X'X)^-1
  std::vector<std::string> term_names;  // "(Intercept)", "treatment", "treatment:gender", "age"
  std::vector<std::vector<int>> term_columns;
  std::vector<std::vector<std::string>> term_variables;  // the variables each term involves
  int error_df = 0;                                      // participants - parameters
};

// Intercept; between factors fully crossed with sum-to-zero contrasts (contr.sum);
// covariates added as they are (already centred). Throws when X is rank-deficient.
BetweenModel between_model(const RmData& data);

// All subsets of the within factors in R's term order (by size, then factor order),
// starting with the empty set (the between-participants stratum).
std::vector<std::vector<int>> within_effects(int factor_count);

// Orthonormal within contrasts of an effect: cells x d, the Kronecker product over factors
// of an orthonormal contrast basis (factors in the effect) or the normalised mean (others).
Eigen::MatrixXd within_contrast(const RmData& data, const std::vector<int>& effect);

}  // namespace handlab::stats
