#include "core/retarget/fingertip_solver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <utility>

#include <Eigen/Cholesky>

namespace handlab::retarget {
namespace {

constexpr double kTranslationUnit = FingertipSolver::kTranslationUnit;
constexpr double kDipPerPip = 2.0 / 3.0;

// Fixed-capacity storage: the solver's vectors and matrices live on the stack, so a frame
// costs no allocation. A hand has 21 DOFs (24 variables with the root translation).
constexpr int kMaxVariables = 48;
constexpr int kMaxFeatureColumns = 32;
using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxVariables, 1>;
using Matrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxVariables, kMaxVariables>;
using FeatureJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxFeatureColumns>;

// Cholesky factorisation A = LL' of a small symmetric positive definite matrix, and solves
// with it. L is stored transposed (column i holds row i of L), so that every inner product
// and update runs over contiguous memory, and only within the envelope: row i of L is zero
// left of row i of A's first non-zero, so an arrowhead matrix (fingers coupled only through
// the root translation, ordered last) factorises at the cost of its blocks. At these sizes
// (4 to 24) Eigen's blocked kernels cost more than the arithmetic.
class SmallCholesky {
 public:
  explicit SmallCholesky(const Matrix& a) : n_(int(a.rows())), lt_(n_, n_) {
    for (int i = 0; i < n_; ++i) {
      int f = 0;
      while (f < i && a(i, f) == 0.0) ++f;
      first_[std::size_t(i)] = f;
    }
    for (int j = 0; j < n_; ++j) {
      const int fj = first_[std::size_t(j)];
      const double d =
          std::sqrt(std::max(a(j, j) - lt_.col(j).segment(fj, j - fj).squaredNorm(), 1e-300));
      lt_(j, j) = d;
      for (int i = j + 1; i < n_; ++i) {
        const int lo = std::max(fj, first_[std::size_t(i)]);
        if (lo > j) continue;  // outside row i's envelope
        lt_(j, i) =
            (a(i, j) - lt_.col(i).segment(lo, j - lo).dot(lt_.col(j).segment(lo, j - lo))) / d;
      }
    }
  }
  // v <- L^-1 v, for a v whose first `from` entries are zero.
  void forward_in_place(Vector& v, int from = 0) const {
    for (int i = from; i < n_; ++i) {
      const int lo = std::max(from, first_[std::size_t(i)]);
      v(i) = (v(i) - lt_.col(i).segment(lo, i - lo).dot(v.segment(lo, i - lo))) / lt_(i, i);
    }
  }
  // v <- L'^-1 v
  void backward_in_place(Vector& v) const {
    for (int i = n_ - 1; i >= 0; --i) {
      const int lo = first_[std::size_t(i)];
      v(i) /= lt_(i, i);
      v.segment(lo, i - lo) -= v(i) * lt_.col(i).segment(lo, i - lo);
    }
  }
  // v <- A^-1 v
  void solve_in_place(Vector& v) const {
    forward_in_place(v);
    backward_in_place(v);
  }

 private:
  int n_;
  Matrix lt_;                               // L', upper triangle within the envelope
  std::array<int, kMaxVariables> first_{};  // per row, the first column of the envelope
};

// One Gauss-Newton step of a block of variables: min 1/2 s'Hs + g's subject to
// lower <= x + s <= upper, by an active-set loop on the linearised problem. The active
// bounds (state -1 lower, +1 upper) are equality constraints C s = b; with H = LL' the KKT
// system H s + C' lambda = -g, C s = b gives the Schur complement system
// (C H^-1 C') lambda = C H^-1 (-g) - b, and s = H^-1 (-g - C' lambda). C's rows are unit
// vectors, so with Y = L^-1 C' the Schur complement is Y'Y and the correction
// L'^-1 (Y lambda): one forward solve per bound that becomes active, one backward solve per
// pass. Bounds with a multiplier of the wrong sign leave the set, bounds the step would cross
// join it. `mu` receives the multipliers of c(x) >= 0.
void kkt_step(const Matrix& h, const Vector& g, const Vector& x, const Vector& lower,
              const Vector& upper, int* state, Vector& step, Vector& mu) {
  const int size = int(x.size());
  const SmallCholesky llt(h);  // positive definite: the regulariser
  Vector free_step = -g;
  llt.solve_in_place(free_step);
  // Columns L^-1 e_k for the bounds that have been active in this step, computed once each
  // (zero above k).
  Matrix y(size, size);
  std::array<bool, kMaxVariables> have_column{};
  std::array<int, kMaxVariables> active;
  for (int pass = 0; pass < 2 * size + 2; ++pass) {
    int a = 0;
    for (int k = 0; k < size; ++k)
      if (state[k] != 0) active[std::size_t(a++)] = k;
    Vector lambda = Vector::Zero(a);
    step = free_step;
    if (a > 0) {
      Matrix schur(a, a);
      for (int i = 0; i < a; ++i) {
        const int k = active[std::size_t(i)];
        if (!have_column[std::size_t(k)]) {
          Vector column = Vector::Zero(size);
          column(k) = 1.0;
          llt.forward_in_place(column, k);
          y.col(k) = column;
          have_column[std::size_t(k)] = true;
        }
        for (int j = 0; j <= i; ++j) {  // active is ascending: y_k is zero above k
          const int kj = active[std::size_t(j)];
          schur(i, j) = schur(j, i) = y.col(k).tail(size - k).dot(y.col(kj).tail(size - k));
        }
        lambda(i) = free_step(k) - ((state[k] < 0 ? lower(k) : upper(k)) - x(k));
      }
      SmallCholesky(schur).solve_in_place(lambda);
      Vector correction = Vector::Zero(size);
      for (int i = 0; i < a; ++i) {
        const int k = active[std::size_t(i)];
        correction.tail(size - k) += lambda(i) * y.col(k).tail(size - k);
      }
      llt.backward_in_place(correction);
      step -= correction;
    }
    // Multipliers of c(x) >= 0: lower bound c = x - lo (lambda_c = -lambda), upper c = hi - x
    // (lambda_c = lambda). A wrong sign means the bound should be released.
    int release = -1;
    double most_negative = -1e-12;
    for (int i = 0; i < a; ++i) {
      const int k = active[std::size_t(i)];
      const double m = state[k] < 0 ? -lambda(i) : lambda(i);
      if (m < most_negative) {
        most_negative = m;
        release = k;
      }
    }
    if (release >= 0) {
      state[release] = 0;
      continue;
    }
    // Bounds the free variables would cross join the active set (never an unbounded one).
    int enter = -1;
    double worst = 1e-15;
    for (int k = 0; k < size; ++k) {
      if (state[k] != 0) continue;
      const double over = std::max(x(k) + step(k) - upper(k), lower(k) - x(k) - step(k));
      if (over > worst) {
        worst = over;
        enter = k;
      }
    }
    if (enter >= 0) {
      state[enter] = x(enter) + step(enter) > upper(enter) ? 1 : -1;
      continue;
    }
    mu.setZero(size);
    for (int i = 0; i < a; ++i) {
      const int k = active[std::size_t(i)];
      mu(k) = state[k] < 0 ? -lambda(i) : lambda(i);
    }
    return;
  }
}

}  // namespace

struct FingertipSolver::Linearisation {
  double value = 0.0;      // 1/2 sum_i w_i |f_i - t_i|^2
  double max_error = 0.0;  // max_i |f_i - t_i|
  Vector gradient;         // J'W(f - t)
  Matrix hessian;          // J'WJ
};

FingertipSolver::FingertipSolver(const hand::Skeleton& skeleton, std::vector<Feature> features,
                                 SolverOptions options)
    : skeleton_(skeleton), features_(std::move(features)), options_(options) {
  const int n = int(skeleton.dofs.size());
  if (n + 3 > kMaxVariables) throw std::invalid_argument("FingertipSolver: too many DOFs");
  const bool free_root = options_.root_translation_weight > 0;
  const int size = n + (free_root ? 3 : 0);
  // The regulariser's constant Hessian. Spatial term: each finger's DIP flexion follows its
  // PIP flexion, DIP ~ 2/3 PIP in natural motion, as sum_f (dip_f - 2/3 pip_f)^2.
  regulariser_hessian_ = Eigen::MatrixXd::Zero(size, size);
  for (const char* finger : {"index", "middle", "ring", "pinky"}) {
    const int pip = skeleton.dof_index(std::string(finger) + "_pip_flexion");
    const int dip = skeleton.dof_index(std::string(finger) + "_dip_flexion");
    if (pip < 0 || dip < 0) continue;
    interphalangeal_.push_back({dip, pip});
    Eigen::VectorXd l = Eigen::VectorXd::Zero(size);
    l(dip) = 1.0;
    l(pip) = -kDipPerPip;
    regulariser_hessian_ += options_.spatial_weight * l * l.transpose();
  }
  regulariser_hessian_.diagonal().head(n).array() += options_.temporal_weight;
  if (free_root)
    regulariser_hessian_.diagonal().tail<3>().array() +=
        options_.root_translation_weight * kTranslationUnit * kTranslationUnit;
  // The DOFs that move each feature: the chain from its marker's bone to the root, minus
  // (for a relative feature) the other marker's chain; a DOF on both chains moves both.
  for (const Feature& f : features_) {
    std::vector<int> sign(std::size_t(n), 2);  // 2: not on either chain
    auto mark = [&](int marker, int s) {
      for (int b = skeleton.markers[std::size_t(marker)].bone; b >= 0;
           b = skeleton.bones[std::size_t(b)].parent) {
        const hand::Bone& bone = skeleton.bones[std::size_t(b)];
        for (int k = bone.first_dof; k < bone.first_dof + bone.dof_count; ++k)
          sign[std::size_t(k)] = sign[std::size_t(k)] == 2 ? s : 0;
      }
    };
    mark(f.marker, 1);
    if (f.relative_to >= 0) mark(f.relative_to, -1);
    FeatureColumns c;
    for (int k = 0; k < n; ++k)
      if (sign[std::size_t(k)] != 2) {
        c.dofs.push_back(k);
        c.sign.push_back(sign[std::size_t(k)]);
      }
    if (int(c.dofs.size()) + 3 > kMaxFeatureColumns)
      throw std::invalid_argument("FingertipSolver: a feature moves too many DOFs");
    columns_.push_back(std::move(c));
  }
  // Connected components of the variables. The root translation, when it is free, comes
  // last: it couples every finger it reaches, and ordered last it leaves the block's matrix
  // an arrowhead that factorises without fill-in.
  std::vector<int> parent(static_cast<std::size_t>(size));
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int v) {
    while (parent[std::size_t(v)] != v)
      v = parent[std::size_t(v)] = parent[std::size_t(parent[std::size_t(v)])];
    return v;
  };
  auto join = [&](int a, int b) { parent[std::size_t(root(a))] = root(b); };
  for (std::size_t i = 0; i < features_.size(); ++i) {
    std::vector<int> vars;
    if (free_root && features_[i].relative_to < 0) vars = {n, n + 1, n + 2};
    for (int k : columns_[i].dofs) vars.push_back(k);
    for (std::size_t k = 1; k < vars.size(); ++k) join(vars[0], vars[k]);
  }
  for (const auto& [dip, pip] : interphalangeal_) join(dip, pip);
  std::vector<int> block_of(static_cast<std::size_t>(size), -1);
  for (int v = 0; v < size; ++v) {
    int& b = block_of[std::size_t(root(v))];
    if (b < 0) {
      b = int(blocks_.size());
      blocks_.emplace_back();
    }
    blocks_[std::size_t(b)].push_back(v);
  }
  scratch_pose_ = hand::HandPose::rest(skeleton);
  hand::forward_kinematics(skeleton, scratch_pose_, frames_);
}

FingertipSolver::~FingertipSolver() = default;

void FingertipSolver::linearise(const hand::HandPose& pose, Eigen::Ref<const Eigen::VectorXd> x,
                                const std::vector<Eigen::Vector3d>& targets, Linearisation& out,
                                hand::BoneFrames& frames, hand::HandPose& scratch,
                                bool derivatives) const {
  const int n = int(skeleton_.dofs.size());
  const int size = int(x.size());
  const bool free_root = size == n + 3;
  scratch.root_rotation = pose.root_rotation;
  scratch.root_position = pose.root_position;
  if (free_root) scratch.root_position += kTranslationUnit * x.tail<3>();
  scratch.angles = x.head(n);
  hand::forward_kinematics(skeleton_, scratch, frames);
  out.value = out.max_error = 0.0;
  if (derivatives) {
    out.gradient.setZero(size);
    out.hessian.setZero(size, size);
  }
  std::array<int, kMaxFeatureColumns> variable;
  FeatureJacobian j;
  for (std::size_t i = 0; i < features_.size(); ++i) {
    const Feature& f = features_[i];
    const FeatureColumns& c = columns_[i];
    const Eigen::Vector3d p = hand::marker_position(skeleton_, frames, f.marker);
    const Eigen::Vector3d q = f.relative_to >= 0
                                  ? hand::marker_position(skeleton_, frames, f.relative_to)
                                  : Eigen::Vector3d::Zero();
    const Eigen::Vector3d d = p - q - targets[i];
    out.value += 0.5 * f.weight * d.squaredNorm();
    out.max_error = std::max(out.max_error, d.norm());
    if (!derivatives) continue;
    int count = 0;
    j.resize(3, Eigen::Index(c.dofs.size()) + 3);
    if (free_root && f.relative_to < 0) {  // a difference of markers ignores the root shift
      for (int a = 0; a < 3; ++a) {
        j.col(count) = kTranslationUnit * Eigen::Vector3d::Unit(a);
        variable[std::size_t(count++)] = n + a;
      }
    }
    for (std::size_t k = 0; k < c.dofs.size(); ++k) {
      const int dof = c.dofs[k];
      const Eigen::Vector3d& axis = frames.dof_axis[std::size_t(dof)];
      const Eigen::Vector3d& centre = frames.dof_centre[std::size_t(dof)];
      Eigen::Vector3d column = Eigen::Vector3d::Zero();
      if (c.sign[k] >= 0) column += axis.cross(p - centre);
      if (c.sign[k] <= 0) column -= axis.cross(q - centre);
      j.col(count) = column;
      variable[std::size_t(count++)] = dof;
    }
    for (int a = 0; a < count; ++a) {
      const int va = variable[std::size_t(a)];
      out.gradient(va) += f.weight * j.col(a).dot(d);
      for (int b = 0; b <= a; ++b) {
        const double h = f.weight * j.col(a).dot(j.col(b));
        out.hessian(va, variable[std::size_t(b)]) += h;
        if (b != a) out.hessian(variable[std::size_t(b)], va) += h;
      }
    }
  }
}

double FingertipSolver::regulariser(Eigen::Ref<const Eigen::VectorXd> x,
                                    Eigen::Ref<const Eigen::VectorXd> anchor) const {
  const int n = int(skeleton_.dofs.size());
  const auto q = x.head(n);
  double spatial = 0.0;
  for (const auto& [dip, pip] : interphalangeal_) {
    const double d = q(dip) - kDipPerPip * q(pip);
    spatial += d * d;
  }
  double value = 0.5 * options_.spatial_weight * spatial +
                 0.5 * options_.temporal_weight * (q - anchor).squaredNorm();
  if (x.size() == n + 3)
    value +=
        0.5 * options_.root_translation_weight * (kTranslationUnit * x.tail<3>()).squaredNorm();
  return value;
}

FingertipSolver::Linearisation FingertipSolver::linearise(
    const hand::HandPose& pose, const Eigen::VectorXd& x,
    const std::vector<Eigen::Vector3d>& targets) const {
  Linearisation lin;
  hand::BoneFrames frames;
  hand::HandPose scratch;
  linearise(pose, x, targets, lin, frames, scratch, true);
  return lin;
}

double FingertipSolver::objective(const hand::HandPose& pose, const Eigen::VectorXd& x,
                                  const std::vector<Eigen::Vector3d>& targets,
                                  const Eigen::VectorXd& anchor) const {
  return linearise(pose, x, targets).value + regulariser(x, anchor);
}

Eigen::VectorXd FingertipSolver::gradient(const hand::HandPose& pose, const Eigen::VectorXd& x,
                                          const std::vector<Eigen::Vector3d>& targets,
                                          const Eigen::VectorXd& anchor) const {
  if (x.size() != regulariser_hessian_.rows())
    throw std::invalid_argument("FingertipSolver::gradient: x has the wrong size");
  const int n = int(skeleton_.dofs.size());
  Eigen::VectorXd g = linearise(pose, x, targets).gradient;
  g += regulariser_hessian_ * x;
  g.head(n) -= options_.temporal_weight * anchor;
  return g;
}

SolverResult FingertipSolver::solve(const hand::HandPose& pose,
                                    const std::vector<Eigen::Vector3d>& targets, bool cold_start,
                                    const Eigen::Vector3d& root_shift) {
  const int n = int(skeleton_.dofs.size());
  const bool free_root = options_.root_translation_weight > 0;
  const int size = n + (free_root ? 3 : 0);
  if (pose.angles.size() != n || targets.size() != features_.size())
    throw std::invalid_argument("FingertipSolver: a pose of another skeleton, or too few targets");
  Vector lower = Vector::Constant(size, -INFINITY), upper = Vector::Constant(size, INFINITY);
  for (int k = 0; k < n; ++k) {
    lower(k) = skeleton_.dofs[std::size_t(k)].lower;
    upper(k) = skeleton_.dofs[std::size_t(k)].upper;
  }
  Vector anchor = pose.angles.cwiseMax(lower.head(n)).cwiseMin(upper.head(n));
  // The regulariser is quadratic: its Hessian R'' is constant (block-diagonal like H),
  // its gradient R''x - wt anchor.
  const Eigen::MatrixXd& regulariser_hessian = regulariser_hessian_;
  Vector anchor_pull = Vector::Zero(size);
  anchor_pull.head(n) = options_.temporal_weight * anchor;
  auto regulariser_value = [&](const Vector& v) { return regulariser(v, anchor); };

  Vector x = Vector::Zero(size);
  x.head(n) = anchor;
  if (free_root) x.tail<3>() = root_shift / kTranslationUnit;
  // Active set: -1 at the lower bound, +1 at the upper, 0 free. Start from the bounds the
  // warm start sits on.
  std::array<int, kMaxVariables> state{};
  for (int k = 0; k < n; ++k)
    state[std::size_t(k)] = x(k) <= lower(k) ? -1 : x(k) >= upper(k) ? 1 : 0;
  Vector mu = Vector::Zero(size);

  Linearisation first, second;
  Linearisation *lin = &first, *trial = &second;
  // The linearisation reads the fixed-capacity vector through an Eigen::Ref, without a copy.
  auto linearise_at = [&](const Vector& v, Linearisation& out, bool derivatives = true) {
    linearise(pose, v, targets, out, frames_, scratch_pose_, derivatives);
    return out.value + regulariser_value(v);
  };
  double current = linearise_at(x, *lin);

  // Levenberg-Marquardt damping: at least the residual's share, grown when the Gauss-Newton
  // model overshoots and shrunk when it is trusted; it does not move the solution (a zero
  // step means g + C'lambda = 0).
  double damping = 0.0;
  SolverResult result;
  const int max_iterations = cold_start
                                 ? std::max(options_.cold_start_iterations, options_.max_iterations)
                                 : options_.max_iterations;
  for (int iteration = 0; iteration < max_iterations; ++iteration) {
    result.iterations = iteration + 1;
    // H = J'WJ + R'' is block-diagonal over the blocks (no feature or regulariser term
    // couples two): each takes its step on its own.
    Vector step(size);
    double slope = 0.0;  // g's
    const double damping_floor = options_.residual_damping * std::sqrt(2.0 * current);
    Vector regulariser_gradient = -anchor_pull;
    regulariser_gradient.noalias() += regulariser_hessian * x;
    for (const std::vector<int>& block : blocks_) {
      const int b = int(block.size()), first = block.front();
      Matrix hb(b, b);
      Vector gb(b), xb(b), lb(b), ub(b), sb(b), mb(b);
      std::array<int, kMaxVariables> sb_state;
      if (block.back() - first + 1 == b) {  // ascending and contiguous: copy whole blocks
        hb = lin->hessian.block(first, first, b, b) + regulariser_hessian.block(first, first, b, b);
        gb = lin->gradient.segment(first, b) + regulariser_gradient.segment(first, b);
        xb = x.segment(first, b);
        lb = lower.segment(first, b);
        ub = upper.segment(first, b);
      } else {
        for (int i = 0; i < b; ++i) {
          const int vi = block[std::size_t(i)];
          for (int j = 0; j < b; ++j) {
            const int vj = block[std::size_t(j)];
            hb(i, j) = lin->hessian(vi, vj) + regulariser_hessian(vi, vj);
          }
          gb(i) = lin->gradient(vi) + regulariser_gradient(vi);
          xb(i) = x(vi);
          lb(i) = lower(vi);
          ub(i) = upper(vi);
        }
      }
      hb.diagonal().array() += std::max(damping, damping_floor);
      for (int i = 0; i < b; ++i)
        sb_state[std::size_t(i)] = state[std::size_t(block[std::size_t(i)])];
      kkt_step(hb, gb, xb, lb, ub, sb_state.data(), sb, mb);
      slope += gb.dot(sb);
      for (int i = 0; i < b; ++i) {
        const int vi = block[std::size_t(i)];
        step(vi) = sb(i);
        mu(vi) = mb(i);
        state[std::size_t(vi)] = sb_state[std::size_t(i)];
      }
    }
    // A step longer than the trust radius is shortened to it: the linearisation of a
    // rotation holds over a fraction of a radian, and a longer Gauss-Newton step (along a
    // flat valley, a palm shift traded for finger angles) would only be backtracked. Then
    // backtracking on the true objective: the step keeps every bound for any length in
    // [0, 1]. The full step lands exactly on the active bounds.
    const double longest = step.lpNorm<Eigen::Infinity>();
    double length = longest > options_.trust_radius ? options_.trust_radius / longest : 1.0;
    Vector next = x + length * step;
    if (length == 1.0)
      for (int k = 0; k < size; ++k) {
        if (state[std::size_t(k)] < 0) next(k) = lower(k);
        if (state[std::size_t(k)] > 0) next(k) = upper(k);
      }
    double value = linearise_at(next, *trial);
    // A predicted decrease below the objective's rounding is no test of the step: near the
    // solution the quadratic model is right, so take it whole.
    const bool resolvable = -slope > 1e-10 * current;
    bool shortened = false;  // the trial's derivatives are those of the first length tried
    while (resolvable && length > 1e-4 && value > current + 1e-4 * length * slope) {
      length *= 0.5;
      next = x + length * step;
      value = linearise_at(next, *trial, false);
      shortened = true;
    }
    if (shortened) linearise_at(next, *trial);
    const double decrease = current - value;
    x = next;
    std::swap(lin, trial);  // the accepted point's linearisation is the next iteration's
    current = value;
    damping = shortened ? std::max(10.0 * damping, 1e-6) : 0.25 * damping;
    if ((length * step).lpNorm<Eigen::Infinity>() < options_.step_tolerance ||
        decrease < options_.decrease_tolerance ||
        decrease < options_.relative_decrease_tolerance * value)
      break;
  }
  result.angles = x.head(n);
  if (free_root) result.root_shift = kTranslationUnit * x.tail<3>();
  result.multipliers = mu.head(n);
  for (int k = 0; k < n; ++k)
    if (state[std::size_t(k)] != 0) result.active.push_back(k);
  result.objective = current;
  result.max_feature_error = lin->max_error;
  return result;
}

}  // namespace handlab::retarget
