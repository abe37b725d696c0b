// What the simulator's stage tests share: states of the scripted pinch of the fine cube, one
// run of it a process (pinch_stage; among them the hand gripping the cube: stiffened tets,
// bones turned, flesh pressed on the cube, the cube's corners on the floor), the increment's map
// (positions plus dq, rotations turned by the rotation vector in the world, as the step moves
// them), the Newton matrix assembled as a sparse matrix from its terms (the reference the
// term-by-term operations are checked against), and finite differences along a direction.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include <Eigen/SparseCore>

#include "core/sim/body_energies.h"
#include "core/sim/contact.h"
#include "core/sim/flesh_energy.h"
#include "core/sim/hand_simulator.h"
#include "core/sim/increment.h"
#include "core/sim/newton_matrix.h"
#include "core/sim/newton_terms.h"
#include "core/task/pinch_scene.h"
#include "core/task/pinch_script.h"

namespace handlab::sim::test {

struct GraspScene {
  const PinchScene& scene;         // the run's, kept for the process (pinch_stage)
  HandSimState state;              // after the step that reached `time`
  std::vector<RigidPose> targets;  // the bones' targets of the next step
  double time = 0.0;
};

// The moments of the scripted pinch of the 1 cm cube that the stage tests look at: the approach
// (0.7 s: no contact but the floor's), the closing (1.0 and 1.2 s; at 1.25 s the fingers rest
// on the cube on the floor, its lower corners on the floor) and the grip halfway up the lift
// (2.0 s: both pads on opposite faces, nodes and skin samples inside, stiffened tets).
inline constexpr std::array<double, 5> kPinchStages = {0.7, 1.0, 1.2, 1.25, 2.0};
static_assert(std::ranges::is_sorted(kPinchStages));  // the run ends at the last

// The pinch at one of kPinchStages. The script runs once a process, to the last stage, keeping
// each stage's state: a step depends only on the steps before it, so a stage's state is the one
// a run to that time alone ends in (the stage tests share one executable for this:
// tests/CMakeLists.txt).
inline const GraspScene& pinch_stage(double time) {
  struct Run {
    PinchScene scene = make_pinch_scene(0.01);
    std::vector<GraspScene> stages;
  };
  static const std::unique_ptr<const Run> run = [] {
    auto r = std::make_unique<Run>();
    const PinchScene& scene = r->scene;
    const double h = scene.model.parameters.time_step;
    int steps = 0;
    run_pinch(scene.model, scene.skeleton, scene.script, SimOptions{}, kPinchStages.back(),
              [&](const HandSimState& s) {
                ++steps;
                for (double t : kPinchStages)
                  if (steps == pinch_step_count(t, h))
                    r->stages.push_back(
                        {scene, s,
                         bone_targets(scene.model, scene.skeleton, scene.script.target(t + h)), t});
              });
    return r;
  }();
  for (const GraspScene& g : run->stages)
    if (g.time == time) return g;
  throw std::invalid_argument("pinch_stage: not one of kPinchStages");
}

// The hand gripping the 1 cm cube halfway up the lift.
inline const GraspScene& gripping_fine_cube() {
  return pinch_stage(2.0);
}

// Every term of a step's first evaluation at `s` (its start and its prediction taken to be the
// state itself; the tets' rotations extracted into it), the contacts' last.
inline void add_every_term(const HandSimModel& model, HandSimState& s,
                           const std::vector<RigidPose>& targets, NewtonTerms& terms,
                           const NewtonLayout* layout = nullptr) {
  ThreadPool pool(2);
  FleshBuffers buffers;
  add_flesh(model, s, terms, pool, buffers);
  add_coupling(model, s, terms, layout);
  add_joints(model, s, terms, layout);
  add_tracking(model, s, targets, terms);
  add_gravity(model, s, terms);
  add_kinetic(
      model, s,
      std::vector<Eigen::Vector3d>(std::size_t(model.bone_count() + 1), Eigen::Vector3d::Zero()), s,
      terms);
  terms.first_contact_spring = terms.springs.size();
  terms.first_contact_block = terms.blocks.size();
  std::vector<Contact> contacts;
  find_contacts(model, s, contacts);
  add_contact_energies(model, s, contacts, terms);
}

// The state moved by t dq (the step's increment: core/sim/increment.h).
inline void move_by(const HandSimModel& model, HandSimState& s,
                    std::vector<Eigen::Vector3d>& turned, const Eigen::VectorXd& dq, double t) {
  apply_increment(model, s, turned, dq, t);
}

// A direction through every unknown: positions by up to `length` (m), rotations by up to
// `angle` (rad), deterministic.
inline Eigen::VectorXd direction(const HandSimModel& model, double length, double angle,
                                 double phase = 1.0) {
  Eigen::VectorXd d(model.dof_count());
  for (int i = 0; i < d.size(); ++i) d[i] = std::sin(phase + 7.3 * i);
  for (int b = 0; b <= model.bone_count(); ++b) {
    d.segment<3>(3 * bone_block(model, b)) *= length;
    d.segment<3>(3 * (bone_block(model, b) + 1)) *= angle;
  }
  d.head(3 * model.node_count()) *= length;
  return d;
}

// Only the unknowns of `keep` (node, translation or rotation blocks) of d.
inline Eigen::VectorXd only(const HandSimModel& model, Eigen::VectorXd d, bool nodes,
                            bool translations, bool rotations) {
  if (!nodes) d.head(3 * model.node_count()).setZero();
  for (int b = 0; b <= model.bone_count(); ++b) {
    if (!translations) d.segment<3>(3 * bone_block(model, b)).setZero();
    if (!rotations) d.segment<3>(3 * (bone_block(model, b) + 1)).setZero();
  }
  return d;
}

// Empty terms for an evaluation, at the model's h^2.
inline NewtonTerms empty_terms(const HandSimModel& model, bool hessian) {
  NewtonTerms t;
  t.scale = model.parameters.time_step * model.parameters.time_step;
  t.clear(model.dof_count(), hessian);
  return t;
}

// A tet's block (a, b) of the matrix from its terms; block (b, a) is its transpose.
inline Eigen::Matrix3d tet_block(const NewtonTerms& terms, std::size_t e, int a, int b) {
  const TetTerms4& t = terms.tets[e / kTetBatch];
  const int l = int(e % kTetBatch);
  Eigen::Vector3d ra, rb, qa, qb;
  for (int i = 0; i < 3; ++i) {
    ra[i] = t.rotated[3 * a + i][l];
    rb[i] = t.rotated[3 * b + i][l];
    qa[i] = t.q[3 * a + i][l];
    qb[i] = t.q[3 * b + i][l];
  }
  Eigen::Matrix3d block = t.vmu[l] * rb * ra.transpose() + t.vlambda[l] * ra * rb.transpose();
  block.diagonal().array() += t.vmu[l] * ra.dot(rb);
  return block + qa * qb.transpose();
}

// The matrix the terms stand for, assembled entry by entry; with `masses`, the node masses
// (the flesh's kinetic Hessian, which the product takes from the model) included.
inline Eigen::SparseMatrix<double> assembled(const HandSimModel& model, const NewtonTerms& terms,
                                             bool masses = true) {
  std::vector<Eigen::Triplet<double>> entries;
  auto add = [&](int bi, int bj, const Eigen::Matrix3d& m) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) entries.emplace_back(3 * bi + r, 3 * bj + c, m(r, c));
  };
  if (masses)
    for (int n = 0; n < model.node_count(); ++n)
      add(n, n, model.node_mass[std::size_t(n)] * Eigen::Matrix3d::Identity());
  if (!terms.tets.empty())
    for (std::size_t e = 0; e < model.tets.size(); ++e) {
      const auto& ids = model.tets[e].nodes;
      for (int a = 0; a < 4; ++a)
        for (int b = a; b < 4; ++b) {
          const Eigen::Matrix3d block = tet_block(terms, e, a, b);
          add(ids[std::size_t(a)], ids[std::size_t(b)], block);
          if (a != b) add(ids[std::size_t(b)], ids[std::size_t(a)], block.transpose());
        }
    }
  for (const SpringTerm& t : terms.springs)
    for (int a = 0; a < t.p.count; ++a)
      for (int b = 0; b < t.p.count; ++b)
        add(t.p.block[std::size_t(a)], t.p.block[std::size_t(b)],
            t.p.j[std::size_t(a)].transpose() * t.k * t.p.j[std::size_t(b)]);
  for (const BlockTerm& t : terms.blocks) add(t.block, t.block, t.m);
  Eigen::SparseMatrix<double> m(model.dof_count(), model.dof_count());
  m.setFromTriplets(entries.begin(), entries.end());
  return m;
}

// Central differences of f along t in [-step, step]: the first derivative and the second.
template <class F>
std::pair<double, double> differences(const F& f, double step) {
  const double plus = f(step), minus = f(-step), centre = f(0.0);
  return {(plus - minus) / (2 * step), (plus - 2 * centre + minus) / (step * step)};
}

}  // namespace handlab::sim::test
