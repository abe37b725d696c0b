#include "core/retarget/fingertip_solver.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace handlab::retarget {

FingertipSolver::FingertipSolver(const hand::Skeleton& skeleton, std::vector<Feature> features, SolverOptions options)
    : skeleton_(skeleton), features_(std::move(features)), options_(options) {
  const int n = int(skeleton.dofs.size());
  smoothness_ = Eigen::MatrixXd::Zero(n, n);
  // Interphalangeal coupling: each finger's DIP flexion follows its PIP flexion.
  for (const char* finger : {"index", "middle", "ring", "pinky"}) {
    const int pip = skeleton.dof_index(std::string(finger) + "_pip_flexion");
    const int dip = skeleton.dof_index(std::string(finger) + "_dip_flexion");
    if (pip < 0 || dip < 0) continue;
    Eigen::VectorXd l = Eigen::VectorXd::Zero(n);
    l(dip) = 1.0;
    l(pip) = -2.0 / 3.0;  // DIP ~ 2/3 PIP in natural motion
    smoothness_ += l * l.transpose();
  }
}

void FingertipSolver::evaluate(const hand::HandPose& pose, const Eigen::VectorXd& angles,
                               const std::vector<Eigen::Vector3d>& targets, Eigen::VectorXd* residual,
                               Eigen::MatrixXd* jacobian) const {
  hand::HandPose p = pose;
  p.angles = angles;
  const hand::BoneFrames frames = hand::forward_kinematics(skeleton_, p);
  const int m = 3 * int(features_.size()), n = int(angles.size());
  residual->resize(m);
  if (jacobian) jacobian->resize(m, n);
  for (std::size_t i = 0; i < features_.size(); ++i) {
    const Feature& f = features_[i];
    const double w = std::sqrt(f.weight);
    const hand::Marker& marker = skeleton_.markers[std::size_t(f.marker)];
    Eigen::Vector3d value = hand::marker_position(skeleton_, frames, f.marker);
    Eigen::Matrix<double, 3, Eigen::Dynamic> j;
    if (jacobian) j = hand::point_jacobian(skeleton_, frames, p, marker.bone, value).rightCols(n);
    if (f.relative_to >= 0) {
      const Eigen::Vector3d other = hand::marker_position(skeleton_, frames, f.relative_to);
      if (jacobian)
        j -= hand::point_jacobian(skeleton_, frames, p, skeleton_.markers[std::size_t(f.relative_to)].bone, other).rightCols(n);
      value -= other;
    }
    residual->segment<3>(Eigen::Index(3 * i)) = w * (value - targets[i]);
    if (jacobian) jacobian->middleRows<3>(Eigen::Index(3 * i)) = w * j;
  }
}

double FingertipSolver::objective(const hand::HandPose& pose, const Eigen::VectorXd& angles,
                                  const std::vector<Eigen::Vector3d>& targets, const Eigen::VectorXd& anchor) const {
  Eigen::VectorXd r;
  evaluate(pose, angles, targets, &r, nullptr);
  const Eigen::VectorXd d = angles - anchor;
  return 0.5 * r.squaredNorm() + 0.5 * options_.spatial_weight * angles.dot(smoothness_ * angles) +
         0.5 * options_.temporal_weight * d.squaredNorm();
}

Eigen::VectorXd FingertipSolver::gradient(const hand::HandPose& pose, const Eigen::VectorXd& angles,
                                          const std::vector<Eigen::Vector3d>& targets, const Eigen::VectorXd& anchor) const {
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  evaluate(pose, angles, targets, &r, &j);
  return j.transpose() * r + options_.spatial_weight * (smoothness_ * angles) + options_.temporal_weight * (angles - anchor);
}

SolverResult FingertipSolver::solve(const hand::HandPose& pose, const std::vector<Eigen::Vector3d>& targets) const {
  const int n = int(skeleton_.dofs.size());
  Eigen::VectorXd lower(n), upper(n);
  for (int k = 0; k < n; ++k) {
    lower(k) = skeleton_.dofs[std::size_t(k)].lower;
    upper(k) = skeleton_.dofs[std::size_t(k)].upper;
  }
  const Eigen::VectorXd anchor = pose.angles.cwiseMax(lower).cwiseMin(upper);
  SolverResult result;
  Eigen::VectorXd q = anchor;
  // Active set: -1 at the lower bound, +1 at the upper, 0 free. Start from the bounds the
  // warm start sits on.
  std::vector<int> state(std::size_t(n), 0);
  for (int k = 0; k < n; ++k) state[std::size_t(k)] = q(k) <= lower(k) ? -1 : q(k) >= upper(k) ? 1 : 0;
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(n);
  const Eigen::MatrixXd regulariser =
      options_.spatial_weight * smoothness_ + options_.temporal_weight * Eigen::MatrixXd::Identity(n, n);

  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  // Levenberg-Marquardt damping, grown when the Gauss-Newton model overshoots and shrunk
  // when it is trusted; it does not move the solution (a zero step means g + C'lambda = 0).
  double damping = 0.0;
  for (int iteration = 0; iteration < options_.max_iterations; ++iteration) {
    result.iterations = iteration + 1;
    evaluate(pose, q, targets, &r, &j);
    Eigen::MatrixXd h = j.transpose() * j + regulariser;
    h.diagonal().array() += damping;
    const Eigen::VectorXd g = j.transpose() * r + options_.spatial_weight * (smoothness_ * q) + options_.temporal_weight * (q - anchor);
    const Eigen::LLT<Eigen::MatrixXd> llt(h);  // positive definite: the temporal term
    Eigen::VectorXd step;
    // Active-set loop on the linearised problem: min 1/2 s'Hs + g's, s_k = bound_k - q_k on
    // the active set A. KKT: H s + C' lambda = -g, C s = b; with H = LL':
    // (C H^-1 C') lambda = C H^-1 (-g) - b, s = H^-1 (-g - C' lambda).
    for (int pass = 0; pass < 2 * n + 2; ++pass) {
      std::vector<int> active;
      for (int k = 0; k < n; ++k)
        if (state[std::size_t(k)] != 0) active.push_back(k);
      const Eigen::VectorXd free_step = llt.solve(-g);
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(Eigen::Index(active.size()));
      step = free_step;
      if (!active.empty()) {
        const Eigen::Index a = Eigen::Index(active.size());
        Eigen::MatrixXd ct = Eigen::MatrixXd::Zero(n, a);
        Eigen::VectorXd b(a);
        for (Eigen::Index i = 0; i < a; ++i) {
          const int k = active[std::size_t(i)];
          ct(k, i) = 1.0;
          b(i) = (state[std::size_t(k)] < 0 ? lower(k) : upper(k)) - q(k);
        }
        const Eigen::MatrixXd hinv_ct = llt.solve(ct);
        const Eigen::MatrixXd schur = ct.transpose() * hinv_ct;
        Eigen::VectorXd cs(a);
        for (Eigen::Index i = 0; i < a; ++i) cs(i) = free_step(active[std::size_t(i)]);
        lambda = schur.llt().solve(cs - b);
        step = free_step - hinv_ct * lambda;
      }
      // Multipliers of c(q) >= 0: lower bound c = q - lo (lambda_c = -lambda), upper c = hi - q
      // (lambda_c = lambda). A wrong sign means the bound should be released.
      int release = -1;
      double most_negative = -1e-12;
      for (std::size_t i = 0; i < active.size(); ++i) {
        const int k = active[i];
        const double m = state[std::size_t(k)] < 0 ? -lambda(Eigen::Index(i)) : lambda(Eigen::Index(i));
        if (m < most_negative) {
          most_negative = m;
          release = k;
        }
      }
      if (release >= 0) {
        state[std::size_t(release)] = 0;
        continue;
      }
      // Bounds the free variables would cross join the active set.
      int enter = -1;
      double worst = 1e-15;
      for (int k = 0; k < n; ++k) {
        if (state[std::size_t(k)] != 0) continue;
        const double over = std::max(q(k) + step(k) - upper(k), lower(k) - q(k) - step(k));
        if (over > worst) {
          worst = over;
          enter = k;
        }
      }
      if (enter >= 0) {
        state[std::size_t(enter)] = q(enter) + step(enter) > upper(enter) ? 1 : -1;
        continue;
      }
      mu.setZero();
      for (std::size_t i = 0; i < active.size(); ++i) {
        const int k = active[i];
        mu(k) = state[std::size_t(k)] < 0 ? -lambda(Eigen::Index(i)) : lambda(Eigen::Index(i));
      }
      break;
    }
    // Backtracking on the true objective: the step keeps every bound for any length in [0, 1].
    const double current = objective(pose, q, targets, anchor);
    const double slope = g.dot(step);
    double length = 1.0;
    Eigen::VectorXd trial = q + step;
    // A predicted decrease below the objective's rounding is no test of the step: near the
    // solution the quadratic model is right, so take it whole.
    const bool resolvable = -slope > 1e-10 * current;
    while (resolvable && length > 1e-4 && objective(pose, trial, targets, anchor) > current + 1e-4 * length * slope) {
      length *= 0.5;
      trial = q + length * step;
    }
    q = trial;
    damping = length < 0.5 ? std::max(10.0 * damping, 1e-6) : 0.25 * damping;
    if (length == 1.0) {
      for (int k = 0; k < n; ++k) {  // exactly on the active bounds
        if (state[std::size_t(k)] < 0) q(k) = lower(k);
        if (state[std::size_t(k)] > 0) q(k) = upper(k);
      }
    }
    if ((length * step).lpNorm<Eigen::Infinity>() < options_.step_tolerance) break;
  }
  result.angles = q;
  result.multipliers = mu;
  for (int k = 0; k < n; ++k)
    if (state[std::size_t(k)] != 0) result.active.push_back(k);
  result.objective = objective(pose, q, targets, anchor);
  return result;
}

}  // namespace handlab::retarget
