// "Ours": the intermediate hand's joint angles that best place its fingertips (and any other
// features) on the scaled tracked ones,
//   min 1/2 (f(q) - f_t)' W (f(q) - f_t) + R(q)   subject to  lower <= q <= upper,
// with R a spatial (interphalangeal smoothness) and temporal (distance to the previous
// frame's solution) regulariser. Gauss-Newton; each step solves the KKT system of the
// linearised problem with the active bounds as equality constraints, by a Cholesky
// factorisation of J'WJ + R'' and a Schur complement for the Lagrange multipliers, and
// updates the active set until the multipliers have the right sign.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "core/hand/skeleton.h"

namespace handlab::retarget {

struct Feature {
  int marker;            // a marker of the skeleton (e.g. "index_tip")
  int relative_to = -1;  // if set, the feature is marker - relative_to (e.g. thumb-index vector)
  double weight = 1.0;
};

struct SolverOptions {
  double spatial_weight = 1e-8;   // (m^2/rad^2): DIP flexion follows PIP flexion
  double temporal_weight = 1e-9;  // (m^2/rad^2): distance to the previous solution
  // Let the wrist position take part (as x = [angles; translation]), pulled towards the
  // given placement with this weight (m^2/m^2); 0 keeps the root fixed.
  double root_translation_weight = 0.0;
  int max_iterations = 16;          // warm-started frames
  int cold_start_iterations = 100;  // the first frame, or after a reset
  double step_tolerance = 1e-6;     // rad (about 1e-7 m at a fingertip)
  // Stop when an iteration lowers the objective by less (m^2, weighted): a step along a
  // flat valley (a palm shift traded for finger angles) moves no tip measurably.
  double decrease_tolerance = 1e-13;
  // ... or by less than this fraction of itself: the tips then move by under half a percent
  // of their distance to the targets, where the rest is a compromise (a target out of reach)
  // that further iterations only slide along a flat valley.
  double relative_decrease_tolerance = 1e-2;
  // Levenberg-Marquardt damping mu |F| on the Gauss-Newton matrix's diagonal, F the weighted
  // residuals of the tips and the regularisers (Fan & Yuan 2005, delta = 1), in m/rad^2. Far
  // from a fit it bounds the step where a finger near a straight pose leaves J'WJ nearly
  // singular (a Gauss-Newton step of radians, then backtracked); it vanishes with the
  // residual, so an exact fit still converges quadratically (a compromise's last digits
  // converge linearly, which the relative stop cuts short). 0: Gauss-Newton.
  double residual_damping = 0.003;
  // The longest step an iteration takes (rad; the root translation counts in units of 5 cm).
  double trust_radius = 0.35;
};

struct SolverResult {
  Eigen::VectorXd angles;
  Eigen::Vector3d root_shift = Eigen::Vector3d::Zero();  // added to the root position
  int iterations = 0;
  std::vector<int> active;      // DOF indices at a bound at the solution
  Eigen::VectorXd multipliers;  // per DOF, >= 0 on active bounds, 0 elsewhere
  double objective = 0.0;
  double max_feature_error = 0.0;  // m: the farthest feature from its target, unweighted
};

// Not thread-safe: solve() reuses the solver's scratch space, so that a warm-started frame
// allocates nothing but its result.
class FingertipSolver {
 public:
  FingertipSolver(const hand::Skeleton& skeleton, std::vector<Feature> features,
                  SolverOptions options = {});
  ~FingertipSolver();

  // Root rotation fixed (in `pose`); its angles are the warm start and the temporal
  // anchor. With a root translation weight, the root position may shift from `pose`'s,
  // starting from `root_shift` (the previous frame's).
  SolverResult solve(const hand::HandPose& pose, const std::vector<Eigen::Vector3d>& targets,
                     bool cold_start = false,
                     const Eigen::Vector3d& root_shift = Eigen::Vector3d::Zero());

  // The root shift enters the variables in this unit (m), so that its Jacobian columns are as
  // large as the joint angles' (lever arms of a few centimetres per radian).
  static constexpr double kTranslationUnit = 0.05;

  // The objective and its gradient at x = angles (root fixed) or [angles; root shift /
  // kTranslationUnit], with the temporal anchor's angles (for KKT checks).
  Eigen::VectorXd gradient(const hand::HandPose& pose, const Eigen::VectorXd& x,
                           const std::vector<Eigen::Vector3d>& targets,
                           const Eigen::VectorXd& anchor) const;
  double objective(const hand::HandPose& pose, const Eigen::VectorXd& x,
                   const std::vector<Eigen::Vector3d>& targets,
                   const Eigen::VectorXd& anchor) const;
  const std::vector<Feature>& features() const { return features_; }

 private:
  // The data term's value, and (with derivatives) its gradient and Gauss-Newton Hessian at x.
  struct Linearisation;
  struct FeatureColumns {
    std::vector<int> dofs;  // the DOFs that move the feature
    std::vector<int> sign;  // +1 from the marker's chain, -1 from relative_to's, 0 both
  };
  void linearise(const hand::HandPose& pose, Eigen::Ref<const Eigen::VectorXd> x,
                 const std::vector<Eigen::Vector3d>& targets, Linearisation& out,
                 hand::BoneFrames& frames, hand::HandPose& scratch, bool derivatives) const;
  // The same with its own scratch space (objective() and gradient(), for tests).
  Linearisation linearise(const hand::HandPose& pose, const Eigen::VectorXd& x,
                          const std::vector<Eigen::Vector3d>& targets) const;
  double regulariser(Eigen::Ref<const Eigen::VectorXd> x,
                     Eigen::Ref<const Eigen::VectorXd> anchor) const;

  const hand::Skeleton& skeleton_;
  std::vector<Feature> features_;
  std::vector<FeatureColumns> columns_;
  std::vector<std::vector<int>> blocks_;  // variables coupled by a feature or the regulariser
  SolverOptions options_;
  std::vector<std::array<int, 2>> interphalangeal_;  // (DIP, PIP) of each finger
  Eigen::MatrixXd regulariser_hessian_;              // constant: R is quadratic
  hand::BoneFrames frames_;                          // scratch
  hand::HandPose scratch_pose_;
};

}  // namespace handlab::retarget
