#include "core/retarget/fingertip_solver.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace handlab::retarget {
namespace {

// The root translation enters the solver in units of 5 cm, so that its Jacobian columns are
// as large as the joint angles' (lever arms of a few centimetres per radian).
constexpr double kTranslationUnit = 0.05;

}  // namespace

FingertipSolver::FingertipSolver(const hand::Skeleton& skeleton, std::vector<Feature> features,
                                 SolverOptions options)
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

void FingertipSolver::evaluate(const hand::HandPose& pose, const Eigen::VectorXd& x,
                               const std::vector<Eigen::Vector3d>& targets,
                               Eigen::VectorXd* residual, Eigen::MatrixXd* jacobian) const {
  const int n = int(skeleton_.dofs.size());
  const int offset = int(x.size()) - n;  // 3 when the root translation is a variable
  hand::HandPose p = pose;
  p.angles = x.tail(n);
  if (offset == 3) p.root_position += kTranslationUnit * x.head<3>();
  const Eigen::VectorXd& angles = x;
  const hand::BoneFrames frames = hand::forward_kinematics(skeleton_, p);
  const int m = 3 * int(features_.size());
  residual->resize(m);
  if (jacobian) jacobian->resize(m, angles.size());
  for (std::size_t i = 0; i < features_.size(); ++i) {
    const Feature& f = features_[i];
    const double w = std::sqrt(f.weight);
    const hand::Marker& marker = skeleton_.markers[std::size_t(f.marker)];
    Eigen::Vector3d value = hand::marker_position(skeleton_, frames, f.marker);
    // Columns: the root translation (when a variable), then the joint angles.
    auto columns = [&](const Eigen::Matrix<double, 3, Eigen::Dynamic>& full) {
      Eigen::Matrix<double, 3, Eigen::Dynamic> out(3, offset + n);
      if (offset == 3) out.leftCols<3>() = kTranslationUnit * full.leftCols<3>();
      out.rightCols(n) = full.rightCols(n);
      return out;
    };
    Eigen::Matrix<double, 3, Eigen::Dynamic> j;
    if (jacobian) j = columns(hand::point_jacobian(skeleton_, frames, p, marker.bone, value));
    if (f.relative_to >= 0) {
      const Eigen::Vector3d other = hand::marker_position(skeleton_, frames, f.relative_to);
      if (jacobian)
        j -= columns(hand::point_jacobian(
            skeleton_, frames, p, skeleton_.markers[std::size_t(f.relative_to)].bone, other));
      value -= other;
    }
    residual->segment<3>(Eigen::Index(3 * i)) = w * (value - targets[i]);
    if (jacobian) jacobian->middleRows<3>(Eigen::Index(3 * i)) = w * j;
  }
}

Eigen::MatrixXd FingertipSolver::regulariser_hessian(int size) const {
  const int n = int(skeleton_.dofs.size()), offset = size - n;
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(size, size);
  h.bottomRightCorner(n, n) = options_.spatial_weight * smoothness_;
  h.diagonal().tail(n).array() += options_.temporal_weight;
  if (offset == 3)
    h.diagonal().head<3>().array() +=
        options_.root_translation_weight * kTranslationUnit * kTranslationUnit;
  return h;
}

Eigen::VectorXd FingertipSolver::regulariser_gradient(const Eigen::VectorXd& x,
                                                      const Eigen::VectorXd& anchor) const {
  const int n = int(skeleton_.dofs.size());
  Eigen::VectorXd g = regulariser_hessian(int(x.size())) * x;
  g.tail(n) -= options_.temporal_weight * anchor;  // the temporal term pulls towards the anchor
  return g;
}

double FingertipSolver::objective(const hand::HandPose& pose, const Eigen::VectorXd& x,
                                  const std::vector<Eigen::Vector3d>& targets,
                                  const Eigen::VectorXd& anchor) const {
  Eigen::VectorXd r;
  evaluate(pose, x, targets, &r, nullptr);
  const int n = int(skeleton_.dofs.size());
  const Eigen::VectorXd q = x.tail(n);
  double value = 0.5 * r.squaredNorm() + 0.5 * options_.spatial_weight * q.dot(smoothness_ * q) +
                 0.5 * options_.temporal_weight * (q - anchor).squaredNorm();
  if (x.size() == n + 3)
    value +=
        0.5 * options_.root_translation_weight * (kTranslationUnit * x.head<3>()).squaredNorm();
  return value;
}

Eigen::VectorXd FingertipSolver::gradient(const hand::HandPose& pose, const Eigen::VectorXd& x,
                                          const std::vector<Eigen::Vector3d>& targets,
                                          const Eigen::VectorXd& anchor) const {
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  evaluate(pose, x, targets, &r, &j);
  return j.transpose() * r + regulariser_gradient(x, anchor);
}

SolverResult FingertipSolver::solve(const hand::HandPose& pose,
                                    const std::vector<Eigen::Vector3d>& targets,
                                    bool cold_start) const {
  const int n = int(skeleton_.dofs.size());
  const int offset = options_.root_translation_weight > 0 ? 3 : 0;
  const int size = offset + n;
  Eigen::VectorXd lower = Eigen::VectorXd::Constant(size, -INFINITY),
                  upper = Eigen::VectorXd::Constant(size, INFINITY);
  for (int k = 0; k < n; ++k) {
    lower(offset + k) = skeleton_.dofs[std::size_t(k)].lower;
    upper(offset + k) = skeleton_.dofs[std::size_t(k)].upper;
  }
  const Eigen::VectorXd anchor = pose.angles.cwiseMax(lower.tail(n)).cwiseMin(upper.tail(n));
  SolverResult result;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(size);
  x.tail(n) = anchor;
  // Active set: -1 at the lower bound, +1 at the upper, 0 free. Start from the bounds the
  // warm start sits on.
  std::vector<int> state(std::size_t(size), 0);
  for (int k = offset; k < size; ++k)
    state[std::size_t(k)] = x(k) <= lower(k) ? -1 : x(k) >= upper(k) ? 1 : 0;
  Eigen::VectorXd mu = Eigen::VectorXd::Zero(size);
  const Eigen::MatrixXd regulariser = regulariser_hessian(size);

  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  // Levenberg-Marquardt damping, grown when the Gauss-Newton model overshoots and shrunk
  // when it is trusted; it does not move the solution (a zero step means g + C'lambda = 0).
  double damping = 0.0;
  const int max_iterations = cold_start
                                 ? std::max(options_.cold_start_iterations, options_.max_iterations)
                                 : options_.max_iterations;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    result.iterations = iteration + 1;
    evaluate(pose, x, targets, &r, &j);
    Eigen::MatrixXd h = j.transpose() * j + regulariser;
    h.diagonal().array() += damping;
    const Eigen::VectorXd g = j.transpose() * r + regulariser_gradient(x, anchor);
    const Eigen::LLT<Eigen::MatrixXd> llt(h);  // positive definite: the regulariser
    Eigen::VectorXd step;
    // Active-set loop on the linearised problem: min 1/2 s'Hs + g's, s_k = bound_k - x_k on
    // the active set A. KKT: H s + C' lambda = -g, C s = b; with H = LL':
    // (C H^-1 C') lambda = C H^-1 (-g) - b, s = H^-1 (-g - C' lambda).
    for (int pass = 0; pass < 2 * size + 2; ++pass) {
      std::vector<int> active;
      for (int k = 0; k < size; ++k)
        if (state[std::size_t(k)] != 0) active.push_back(k);
      const Eigen::VectorXd free_step = llt.solve(-g);
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(Eigen::Index(active.size()));
      step = free_step;
      if (!active.empty()) {
        const Eigen::Index a = Eigen::Index(active.size());
        Eigen::MatrixXd ct = Eigen::MatrixXd::Zero(size, a);
        Eigen::VectorXd b(a);
        for (Eigen::Index i = 0; i < a; ++i) {
          const int k = active[std::size_t(i)];
          ct(k, i) = 1.0;
          b(i) = (state[std::size_t(k)] < 0 ? lower(k) : upper(k)) - x(k);
        }
        const Eigen::MatrixXd hinv_ct = llt.solve(ct);
        const Eigen::MatrixXd schur = ct.transpose() * hinv_ct;
        Eigen::VectorXd cs(a);
        for (Eigen::Index i = 0; i < a; ++i) cs(i) = free_step(active[std::size_t(i)]);
        lambda = schur.llt().solve(cs - b);
        step = free_step - hinv_ct * lambda;
      }
      // Multipliers of c(x) >= 0: lower bound c = x - lo (lambda_c = -lambda), upper c = hi - x
      // (lambda_c = lambda). A wrong sign means the bound should be released.
      int release = -1;
      double most_negative = -1e-12;
      for (std::size_t i = 0; i < active.size(); ++i) {
        const int k = active[i];
        const double m =
            state[std::size_t(k)] < 0 ? -lambda(Eigen::Index(i)) : lambda(Eigen::Index(i));
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
      for (int k = offset; k < size; ++k) {
        if (state[std::size_t(k)] != 0) continue;
        const double over = std::max(x(k) + step(k) - upper(k), lower(k) - x(k) - step(k));
        if (over > worst) {
          worst = over;
          enter = k;
        }
      }
      if (enter >= 0) {
        state[std::size_t(enter)] = x(enter) + step(enter) > upper(enter) ? 1 : -1;
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
    const double current = objective(pose, x, targets, anchor);
    const double slope = g.dot(step);
    double length = 1.0;
    Eigen::VectorXd trial = x + step;
    // A predicted decrease below the objective's rounding is no test of the step: near the
    // solution the quadratic model is right, so take it whole.
    const bool resolvable = -slope > 1e-10 * current;
    while (resolvable && length > 1e-4 &&
           objective(pose, trial, targets, anchor) > current + 1e-4 * length * slope) {
      length *= 0.5;
      trial = x + length * step;
    }
    x = trial;
    damping = length < 0.5 ? std::max(10.0 * damping, 1e-6) : 0.25 * damping;
    if (length == 1.0) {
      for (int k = 0; k < size; ++k) {  // exactly on the active bounds
        if (state[std::size_t(k)] < 0) x(k) = lower(k);
        if (state[std::size_t(k)] > 0) x(k) = upper(k);
      }
    }
    if ((length * step).lpNorm<Eigen::Infinity>() < options_.step_tolerance) break;
  }
  result.angles = x.tail(n);
  if (offset == 3) result.root_shift = kTranslationUnit * x.head<3>();
  result.multipliers = mu.tail(n);
  for (int k = offset; k < size; ++k)
    if (state[std::size_t(k)] != 0) result.active.push_back(k - offset);
  result.objective = objective(pose, x, targets, anchor);
  return result;
}

}  // namespace handlab::retarget
