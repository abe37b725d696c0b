// What one evaluation of the step's energy finds: the energy, its gradient, and the Newton
// matrix as the sum of the terms the energies added, kept instead of assembled (conjugate
// gradients multiply by it term by term; newton_matrix.h). Every energy stage adds into one.
// The unknowns come in blocks of three: a flesh node's position, then each bone's translation
// and rotation, then the cube's.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "core/sim/hand_sim_model.h"
#include "core/sim/rigid_body.h"

namespace handlab::sim {

inline int bone_block(const HandSimModel& model, int bone) {
  return model.node_count() + 2 * bone;
}
inline int cube_block(const HandSimModel& model) {
  return model.node_count() + 2 * model.bone_count();
}
inline int block_count(const HandSimModel& model) {
  return model.node_count() + 2 * model.bone_count() + 2;
}

// A point's position as a linear function of the unknowns' increments: dp = sum_k J_k dq_k,
// over at most 6 blocks of 3 unknowns (a tet's nodes, a body's translation and rotation).
struct PointJacobian {
  int count = 0;
  std::array<int, 6> block{};
  std::array<Eigen::Matrix3d, 6> j;
  PointJacobian() {
    for (Eigen::Matrix3d& m : j) m.setZero();  // copies read them all
  }
  void add(int b, const Eigen::Matrix3d& m) {
    block[std::size_t(count)] = b;
    j[std::size_t(count++)] = m;
  }
  // A point of a body at `arm` from its centre of mass, with `sign`: d(c + r) = dc + dtheta x r.
  void add_body_point(int body_block, const Eigen::Vector3d& arm, double sign) {
    add(body_block, sign * Eigen::Matrix3d::Identity());
    add(body_block + 1, -sign * cross_matrix(arm));
  }
};

// The tets' terms, per node pair vmu [(r_a . r_b) I + r_b r_a'] + vlambda r_a r_b' + q_a q_b'
// (r_a = R grad N_a, vmu = V mu, vlambda = V lambda, q the stiffening's rank-one part, zero
// below its threshold), four tets a batch: tet 4k + l in SIMD lane l of batch k, so that the
// evaluation, the products and the assembly work in the vector unit's lanes. A batch past the
// last tet repeats it with no terms.
using Lane4 = Eigen::Array4d;
constexpr int kTetBatch = 4;
struct TetTerms4 {
  Lane4 rotated[12];  // r_a's entry i at 3a + i
  Lane4 q[12];
  Lane4 vmu, vlambda;
};

// Where a 3x3 block of the matrix lies among the factorisation's panels (the ordering keeps a
// block's unknowns together): entry (r, c) of the block at at + r + stride c, or of its
// transpose when the ordering stores the block as its mirror. at = -1: a block whose mirror
// writes the place.
struct PanelBlock {
  int at = -1, stride = 0;
  bool transposed = false;
};

struct SpringTerm {  // J'KJ
  PointJacobian p;
  Eigen::Matrix3d k;
  const PanelBlock* cached;  // its blocks' places (NewtonLayout's), or null
};
struct BlockTerm {  // on one diagonal block
  int block;
  Eigen::Matrix3d m;
};
using Matrix6d = Eigen::Matrix<double, 6, 6>;

struct NewtonTerms {
  double scale = 1.0;        // h^2: the potential's terms enter the system scaled by it
  bool with_hessian = true;  // false: the energy alone (the line search)
  double energy = 0.0;       // h^2 times the step's energy
  Eigen::VectorXd gradient;
  std::vector<TetTerms4> tets;  // batches of four tets
  std::vector<SpringTerm> springs;
  std::vector<BlockTerm> blocks;
  // The contacts' terms come last: springs and blocks from these on are theirs.
  std::size_t first_contact_spring = 0, first_contact_block = 0;

  // A term on a diagonal block of the matrix.
  void add_block(int b, const Eigen::Matrix3d& m) {
    if (with_hessian) blocks.push_back({b, m});
  }

  // The energy 1/2 d'Kd of a point's offset d (K symmetric positive semidefinite): gradient
  // J'Kd, Gauss-Newton Hessian J'KJ. `cached`, when given, holds each block pair's place
  // in the panels (NewtonLayout), so that assembling the fixed springs (coupling, joints)
  // needs no search.
  void add_spring(const PointJacobian& p, const Eigen::Matrix3d& k, const Eigen::Vector3d& d,
                  const PanelBlock* cached = nullptr) {
    const Eigen::Vector3d f = scale * (k * d);
    energy += 0.5 * d.dot(f);
    for (int a = 0; a < p.count; ++a)
      gradient.segment<3>(3 * p.block[std::size_t(a)]) += p.j[std::size_t(a)].transpose() * f;
    if (with_hessian) springs.push_back({p, scale * k, cached});
  }

  // Only the Hessian J'KJ of a spring (no energy or force).
  void add_curvature(const PointJacobian& p, const Eigen::Matrix3d& k) {
    if (with_hessian) springs.push_back({p, scale * k, nullptr});
  }

  // A constant force -f on a point at `position` (the energy f . position).
  void add_force(const PointJacobian& p, const Eigen::Vector3d& f,
                 const Eigen::Vector3d& position) {
    energy += scale * f.dot(position);
    for (int a = 0; a < p.count; ++a)
      gradient.segment<3>(3 * p.block[std::size_t(a)]) +=
          scale * p.j[std::size_t(a)].transpose() * f;
  }

  // Empties it for an evaluation of `dofs` unknowns.
  void clear(int dofs, bool hessian) {
    with_hessian = hessian;
    energy = 0.0;
    gradient.setZero(dofs);
    if (hessian) {
      springs.clear();
      blocks.clear();
    }
  }
};

}  // namespace handlab::sim
