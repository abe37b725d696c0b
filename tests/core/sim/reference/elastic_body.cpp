#include "tests/core/sim/reference/elastic_body.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/sim/rotation_extraction.h"

namespace handlab::sim {
namespace {

std::array<Eigen::Vector3d, 4> gather(const std::vector<Eigen::Vector3d>& x, const TetElement& t) {
  return {x[std::size_t(t.nodes[0])], x[std::size_t(t.nodes[1])], x[std::size_t(t.nodes[2])],
          x[std::size_t(t.nodes[3])]};
}

}  // namespace

ElasticBodyModel make_elastic_body(const mesh::TetMesh& mesh, const Material& material,
                                   double density) {
  ElasticBodyModel model;
  model.rest = mesh.nodes;
  model.mass.assign(mesh.nodes.size(), 0.0);
  model.fixed.assign(mesh.nodes.size(), false);
  for (const auto& ids : mesh.tets) {
    const std::array<Eigen::Vector3d, 4> rest = {
        mesh.nodes[std::size_t(ids[0])], mesh.nodes[std::size_t(ids[1])],
        mesh.nodes[std::size_t(ids[2])], mesh.nodes[std::size_t(ids[3])]};
    model.tets.push_back(make_tet_element(rest, ids));
    model.stiffness.push_back(corotated_stiffness(model.tets.back(), material));
    for (int id : ids) model.mass[std::size_t(id)] += density * model.tets.back().volume / 4.0;
  }
  return model;
}

ElasticBodyState rest_state(const ElasticBodyModel& model) {
  ElasticBodyState s;
  s.position = model.rest;
  s.velocity.assign(model.rest.size(), Eigen::Vector3d::Zero());
  s.rotation.assign(model.tets.size(), Eigen::Quaterniond::Identity());
  return s;
}

struct ElasticBodySolver::Impl {
  const ElasticBodyModel& model;
  int dofs = 0;
  Eigen::SparseMatrix<double> matrix;
  // For every tet and node pair (a, b), the value index of entry (3 n_a, 3 n_b + c), c = 0..2;
  // the block's rows follow contiguously (rows are sorted within a column).
  std::vector<std::array<int, 48>> tet_blocks;
  std::vector<std::array<int, 3>> diagonal;  // per node: value index of (3i, 3i + c)
  std::vector<bool> fixed_dof;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  ElementEvaluation element;

  explicit Impl(const ElasticBodyModel& m) : model(m) {
    const int n = int(m.rest.size());
    dofs = 3 * n;
    std::vector<std::set<int>> adjacent(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) adjacent[std::size_t(i)].insert(i);
    for (const auto& t : m.tets)
      for (int a : t.nodes)
        for (int b : t.nodes) adjacent[std::size_t(a)].insert(b);
    std::vector<Eigen::Triplet<double>> entries;
    for (int j = 0; j < n; ++j)
      for (int i : adjacent[std::size_t(j)])
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) entries.emplace_back(3 * i + r, 3 * j + c, 1.0);
    matrix.resize(dofs, dofs);
    matrix.setFromTriplets(entries.begin(), entries.end());
    matrix.makeCompressed();
    auto index_of = [&](int row, int col) {
      const int* rows = matrix.innerIndexPtr();
      const int begin = matrix.outerIndexPtr()[col], end = matrix.outerIndexPtr()[col + 1];
      return int(std::lower_bound(rows + begin, rows + end, row) - rows);
    };
    for (const auto& t : m.tets) {
      std::array<int, 48> blocks;
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          for (int c = 0; c < 3; ++c)
            blocks[std::size_t(12 * a + 3 * b + c)] =
                index_of(3 * t.nodes[std::size_t(a)], 3 * t.nodes[std::size_t(b)] + c);
      tet_blocks.push_back(blocks);
    }
    for (int i = 0; i < n; ++i)
      diagonal.push_back(
          {index_of(3 * i, 3 * i), index_of(3 * i, 3 * i + 1), index_of(3 * i, 3 * i + 2)});
    fixed_dof.assign(std::size_t(dofs), false);
    for (int i = 0; i < n; ++i)
      if (m.fixed[std::size_t(i)])
        for (int r = 0; r < 3; ++r) fixed_dof[std::size_t(3 * i + r)] = true;
    ldlt.analyzePattern(matrix);
  }

  void update_rotations(ElasticBodyState& state) const {
    for (std::size_t e = 0; e < model.tets.size(); ++e)
      extract_rotation(deformation_gradient(model.tets[e], gather(state.position, model.tets[e])),
                       state.rotation[e]);
  }

  // U and its gradient (and Hessian into `matrix`, scaled by `hessian_scale`) at the state.
  double assemble(const ElasticBodyState& state, const std::vector<Eigen::Vector3d>& anchors,
                  const std::vector<Eigen::Vector3d>* forces, Eigen::VectorXd& gradient,
                  double hessian_scale, bool with_hessian) {
    gradient.setZero(dofs);
    if (with_hessian) std::fill(matrix.valuePtr(), matrix.valuePtr() + matrix.nonZeros(), 0.0);
    double energy = 0.0;
    double* values = matrix.valuePtr();
    for (std::size_t e = 0; e < model.tets.size(); ++e) {
      const TetElement& t = model.tets[e];
      evaluate_corotated(model.stiffness[e], gather(model.rest, t), gather(state.position, t),
                         state.rotation[e].toRotationMatrix(), element, with_hessian);
      energy += element.energy;
      for (int a = 0; a < 4; ++a)
        gradient.segment<3>(3 * t.nodes[std::size_t(a)]) += element.gradient.segment<3>(3 * a);
      if (!with_hessian) continue;
      const auto& blocks = tet_blocks[e];
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          for (int c = 0; c < 3; ++c) {
            double* column = values + blocks[std::size_t(12 * a + 3 * b + c)];
            for (int r = 0; r < 3; ++r)
              column[r] += hessian_scale * element.hessian(3 * a + r, 3 * b + c);
          }
    }
    for (std::size_t i = 0; i < model.rest.size(); ++i) {
      const Eigen::Vector3d& x = state.position[i];
      energy -= model.mass[i] * model.gravity.dot(x);
      gradient.segment<3>(Eigen::Index(3 * i)) -= model.mass[i] * model.gravity;
      if (forces) {
        energy -= (*forces)[i].dot(x);
        gradient.segment<3>(Eigen::Index(3 * i)) -= (*forces)[i];
      }
    }
    for (std::size_t s = 0; s < model.springs.size(); ++s) {
      const AnchorSpring& spring = model.springs[s];
      const Eigen::Vector3d d = state.position[std::size_t(spring.node)] - anchors[s];
      energy += 0.5 * spring.stiffness * d.squaredNorm();
      gradient.segment<3>(3 * spring.node) += spring.stiffness * d;
      if (with_hessian)
        for (int c = 0; c < 3; ++c)
          values[diagonal[std::size_t(spring.node)][std::size_t(c)] + c] +=
              hessian_scale * spring.stiffness;
    }
    return energy;
  }

  // Fixed DOFs: identity rows and columns, zero right-hand side.
  void constrain(Eigen::VectorXd& rhs) {
    double* values = matrix.valuePtr();
    const int* rows = matrix.innerIndexPtr();
    for (int col = 0; col < dofs; ++col)
      for (int k = matrix.outerIndexPtr()[col]; k < matrix.outerIndexPtr()[col + 1]; ++k)
        if (fixed_dof[std::size_t(col)] || fixed_dof[std::size_t(rows[k])])
          values[k] = rows[k] == col ? 1.0 : 0.0;
    for (int d = 0; d < dofs; ++d)
      if (fixed_dof[std::size_t(d)]) rhs(d) = 0.0;
  }

  double free_residual(const Eigen::VectorXd& g) const {
    double worst = 0.0;
    for (int d = 0; d < dofs; ++d)
      if (!fixed_dof[std::size_t(d)]) worst = std::max(worst, std::abs(g(d)));
    return worst;
  }

  void solve_and_apply(Eigen::VectorXd& rhs, ElasticBodyState& state) {
    ldlt.factorize(matrix);
    if (ldlt.info() != Eigen::Success)
      throw std::runtime_error("ElasticBodySolver: the Newton system is not positive definite");
    const Eigen::VectorXd dx = ldlt.solve(rhs);
    for (std::size_t i = 0; i < state.position.size(); ++i)
      state.position[i] += dx.segment<3>(Eigen::Index(3 * i));
  }
};

ElasticBodySolver::ElasticBodySolver(const ElasticBodyModel& model)
    : impl_(std::make_unique<Impl>(model)) {}
ElasticBodySolver::~ElasticBodySolver() = default;

double ElasticBodySolver::potential(ElasticBodyState& state,
                                    const std::vector<Eigen::Vector3d>& anchors,
                                    Eigen::VectorXd* gradient) const {
  impl_->update_rotations(state);
  Eigen::VectorXd g;
  const double u = impl_->assemble(state, anchors, nullptr, g, 1.0, false);
  if (gradient) *gradient = g;
  return u;
}

StepReport ElasticBodySolver::step(ElasticBodyState& state,
                                   const std::vector<Eigen::Vector3d>& anchors,
                                   int newton_iterations) {
  const ElasticBodyModel& m = impl_->model;
  if (anchors.size() != m.springs.size())
    throw std::invalid_argument("ElasticBodySolver::step: one anchor per spring");
  const double h = m.time_step;
  const std::vector<Eigen::Vector3d> start = state.position;
  std::vector<Eigen::Vector3d> predicted(start.size());
  for (std::size_t i = 0; i < start.size(); ++i)
    predicted[i] = m.fixed[i] ? start[i] : start[i] + h * state.velocity[i];
  for (std::size_t i = 0; i < start.size(); ++i)
    if (!m.fixed[i]) state.position[i] = predicted[i];
  StepReport report;
  Eigen::VectorXd g;
  for (int it = 0; it < newton_iterations; ++it) {
    impl_->update_rotations(state);
    // h^2 times the backward-Euler energy's gradient and Hessian: M(x - x_pred) + h^2 grad U.
    impl_->assemble(state, anchors, nullptr, g, h * h, true);
    g *= h * h;
    double* values = impl_->matrix.valuePtr();
    for (std::size_t i = 0; i < start.size(); ++i) {
      g.segment<3>(Eigen::Index(3 * i)) += m.mass[i] * (state.position[i] - predicted[i]);
      for (int c = 0; c < 3; ++c) values[impl_->diagonal[i][std::size_t(c)] + c] += m.mass[i];
    }
    report.newton_iterations = it + 1;
    Eigen::VectorXd rhs = -g;
    impl_->constrain(rhs);
    impl_->solve_and_apply(rhs, state);
  }
  for (std::size_t i = 0; i < start.size(); ++i)
    state.velocity[i] =
        m.fixed[i] ? Eigen::Vector3d::Zero().eval() : ((state.position[i] - start[i]) / h).eval();
  report.residual = impl_->free_residual(g) / (h * h);
  return report;
}

StepReport ElasticBodySolver::solve_static(ElasticBodyState& state,
                                           const std::vector<Eigen::Vector3d>& anchors,
                                           const std::vector<Eigen::Vector3d>& forces,
                                           int max_iterations, double tolerance) {
  StepReport report;
  Eigen::VectorXd g;
  for (int it = 0; it < max_iterations; ++it) {
    impl_->update_rotations(state);
    impl_->assemble(state, anchors, &forces, g, 1.0, true);
    report.residual = impl_->free_residual(g);
    if (report.residual < tolerance) break;
    report.newton_iterations = it + 1;
    Eigen::VectorXd rhs = -g;
    impl_->constrain(rhs);
    impl_->solve_and_apply(rhs, state);
  }
  for (auto& v : state.velocity) v.setZero();
  return report;
}

}  // namespace handlab::sim
