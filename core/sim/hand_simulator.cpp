#include "core/sim/hand_simulator.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/sim/box_distance.h"
#include "core/sim/lanes.h"
#include "core/sim/rotation_extraction.h"
#include "core/sim/supernodal_ldlt.h"

namespace handlab::sim {
namespace {

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
};

// A contact candidate, found at the predicted state. Its normal penalty acts whenever the
// point is inside the surface; its friction is decided at the predicted state: an anchor
// spring (sticking) or a kinetic force of mu f_n against the slip (sliding), the latter so that
// the anchor spring's stiffness does not hold back a slide's acceleration.
struct Contact {
  enum Kind { kNodeCube, kNodeFloor, kCornerFloor } kind;
  int point;               // node or corner
  Eigen::Vector3d normal;  // at the predicted state, in the surface's frame (cube or world)
  Eigen::Vector3d anchor;  // friction anchor, in the surface's frame
  bool touching = false;   // inside the surface at the predicted state: friction acts
  // The normal penalty's curvature is in Newton's matrix even where the point is outside:
  // from the start for points inside at the prediction, and from the next pass for points
  // that a pass without it carried inside (contacts_entered), so that a step lands where the
  // penalty balances the push instead of deep inside, and a resting cube does not chatter.
  bool curved = false;
  bool sliding = false;
  Eigen::Vector3d slip = Eigen::Vector3d::Zero();  // surface frame
  double friction_force = 0.0;                     // N
  int switches = 0;  // between sticking and sliding, in this step's passes
  // The normal in the world at the predicted state: the friction spring acts across it, held
  // through the step, so that its energy's gradient is exactly the force it exerts (a normal
  // turning with the cube would add a torque the spring's gradient leaves out, and the line
  // search would find the Newton step uphill).
  Eigen::Vector3d across = Eigen::Vector3d::Zero();
};

// Points this close to a surface (m), beyond what they can move in a step, are candidates.
constexpr double kContactMargin = 0.001;
// How many times a step is taken again when its result disagrees with the contacts it
// assumed (a point that entered a surface unseen, a slide that stopped, a stick that left the
// cone).
constexpr int kFrictionPasses = 4;
// The largest rotation of a body in one Newton iteration (rad).
constexpr double kMaxTurn = 0.25;

const std::array<Eigen::Vector3d, 8>& corner_signs() {
  static const std::array<Eigen::Vector3d, 8> signs = [] {
    std::array<Eigen::Vector3d, 8> s;
    for (int k = 0; k < 8; ++k)
      s[std::size_t(k)] = Eigen::Vector3d(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1);
    return s;
  }();
  return signs;
}

// Coulomb's cone on a friction anchor: the friction spring's force k|t| may reach mu f_n, so
// the anchor may be `limit` = mu f_n / k away; beyond, it slides towards the point until it is.
Eigen::Vector3d coulomb_anchor(const Eigen::Vector3d& x, const Eigen::Vector3d& n, double limit,
                               Eigen::Vector3d anchor) {
  const Eigen::Vector3d t = (Eigen::Matrix3d::Identity() - n * n.transpose()) * (x - anchor);
  const double stretch = t.norm();
  if (stretch > limit) anchor += t * (1.0 - limit / stretch);
  return anchor;
}

// What the step holds fixed while Newton iterates: where it started and its targets.
struct StepFrame {
  const HandSimState* start = nullptr;
  const std::vector<RigidPose>* targets = nullptr;
};

}  // namespace

// The Newton matrix as the sum of the terms an evaluation found, kept instead of assembled:
// conjugate gradients multiply by it term by term (cheaper than assembling it for the few
// iterations a step takes), and it is assembled only when it is to be factorised.
// The tets' terms, per node pair vmu [(r_a . r_b) I + r_b r_a'] + vlambda r_a r_b' + q_a q_b'
// (r_a = R grad N_a, vmu = V mu, vlambda = V lambda, q the stiffening's rank-one part, zero
// below its threshold), four tets a batch: tet 4k + l in lane l of batch k, so that the
// evaluation, the products and the assembly work in the vector unit's lanes. A batch past the
// last tet repeats it with no terms.
using Lane4 = Eigen::Array4d;
struct TetTerms4 {
  Lane4 rotated[12];  // r_a's entry i at 3a + i
  Lane4 q[12];
  Lane4 vmu, vlambda;
};
constexpr int kBatch = 4;
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
  const PanelBlock* cached;  // its blocks' places (see spring_blocks), or null
};
using Matrix6d = Eigen::Matrix<double, 6, 6>;
struct BlockTerm {  // on one diagonal block
  int block;
  Eigen::Matrix3d m;
};

struct HandSimulator::Impl {
  const HandSimModel& model;
  SimOptions options;
  int nodes = 0, bones = 0, blocks = 0, dofs = 0;
  std::vector<TetTerms4> tet_terms;  // batches of four tets
  // The tets as the per-tet loops read them. A TetElement carries its 12x12 stiffness (1.2 kB)
  // that these loops never use: read through it, the mesh's tets span 3.5 MB; these 128 bytes
  // a tet keep them within the L2 cache.
  struct FleshTet {
    std::array<int, 4> nodes;
    double volume;
    Eigen::Matrix<double, 3, 4> gradients;
  };
  std::vector<FleshTet> flesh_tets;
  std::vector<SpringTerm> spring_terms;
  std::vector<BlockTerm> block_terms;
  Eigen::SparseMatrix<double> matrix;  // the matrix as a sparse matrix (assemble)
  // Places in the panels: each tet's 10 node pairs (a <= b), each coupling's and joint's block
  // pairs (add_spring's caches: 36 and 16), each block's diagonal block.
  std::vector<std::array<PanelBlock, 10>> tet_blocks;
  std::vector<PanelBlock> coupling_blocks, joint_blocks, diagonal_blocks;
  int panel_split = 0;            // the first value of lane 1's panels (assemble_panels)
  SupernodalLdlt preconditioner;  // the factorisation in panels, for the solves
  Eigen::VectorXd gradient;
  // An evaluation's terms but the contacts' (Reuse::kKeep): their gradient and energy, and how
  // many of the spring and block terms are theirs (those come first).
  Eigen::VectorXd kept_gradient;
  double kept_energy = 0.0;
  std::size_t kept_springs = 0, kept_blocks = 0;
  // The diagonal of those terms (see diagonal()).
  mutable Eigen::VectorXd base_diagonal;
  mutable bool base_diagonal_known = false;
  Lanes lanes;                               // the per-tet work split (flesh_range)
  std::vector<Eigen::VectorXd> lane_forces;  // lanes 1.. (lane 0 writes into the gradient)
  std::vector<double> lane_energy;
  double scale = 1.0;  // h^2: the potential's terms enter the system scaled by it
  bool with_hessian = true;
  double energy = 0.0;
  std::vector<Contact> contacts;
  bool factorised = false, stale = false;
  // Steps taken, the step of the last factorisation, the solves of this step so far, and the
  // step before which a step's first solve factorises at once (see solve).
  long step_index = 0, factorised_at = -1, direct_until = 0;
  int slow_steps = 0;  // consecutive steps whose first solve took two CG iterations or more
  int solves_this_step = 0;
  // The cube's unknowns; whether the ordering put them last (its many contact candidates make
  // them dense rows), so that the factor's last block can follow the cube's own terms
  // (SupernodalLdlt::modify_trailing); those terms' block when the matrix was last factorised,
  // and the change since that the factor has taken.
  std::vector<int> cube_dofs;
  bool cube_trailing = false;
  Matrix6d cube_factorised, cube_applied;
  // Whether the factor is still the matrix itself, up to the cube's own terms (which
  // modify_trailing follows): the terms an evaluation keeps have not been found anew since it
  // was factorised (terms_found counts those evaluations), and the contact terms on other
  // unknowns than the cube's alone are the same. A step's later passes differ from its first
  // in their contacts only, mostly the floor's corners: after a factorisation they then solve
  // directly instead of by CG.
  long terms_found = 0, factorised_terms = -1;
  int last_iterations = 0;  // CG's in this step's last solve
  std::vector<SpringTerm> factorised_contacts;

  int bone_block(int b) const { return nodes + 2 * b; }
  int cube_block() const { return nodes + 2 * bones; }

  explicit Impl(const HandSimModel& m, SimOptions o)
      : model(m),
        options(o),
        lanes(o.threads),
        lane_forces(std::size_t(o.threads)),
        lane_energy(std::size_t(o.threads)) {
    nodes = m.node_count();
    bones = m.bone_count();
    blocks = nodes + 2 * bones + 2;
    dofs = 3 * blocks;
    for (int k = 0; k < 6; ++k) cube_dofs.push_back(3 * cube_block() + k);
    // Block sparsity: every pair of blocks some energy couples.
    std::vector<std::set<int>> pairs(static_cast<std::size_t>(blocks));
    auto couple = [&](const std::vector<int>& group) {
      for (int a : group)
        for (int b : group) pairs[std::size_t(a)].insert(b);
    };
    for (int b = 0; b < blocks; ++b) pairs[std::size_t(b)].insert(b);
    for (const TetElement& t : m.tets) couple({t.nodes[0], t.nodes[1], t.nodes[2], t.nodes[3]});
    for (const SimCoupling& c : m.coupling)
      couple({c.nodes[0], c.nodes[1], c.nodes[2], c.nodes[3], bone_block(c.bone),
              bone_block(c.bone) + 1});
    for (const SimJoint& j : m.joints)
      couple({bone_block(j.parent), bone_block(j.parent) + 1, bone_block(j.child),
              bone_block(j.child) + 1});
    for (int n : m.surface_nodes) couple({n, cube_block(), cube_block() + 1});
    couple({cube_block(), cube_block() + 1});
    for (int b = 0; b < bones; ++b) couple({bone_block(b), bone_block(b) + 1});
    std::vector<Eigen::Triplet<double>> entries;
    for (int j = 0; j < blocks; ++j)
      for (int i : pairs[std::size_t(j)])
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) entries.emplace_back(3 * i + r, 3 * j + c, 1.0);
    matrix.resize(dofs, dofs);
    matrix.setFromTriplets(entries.begin(), entries.end());
    matrix.makeCompressed();
    // The factorisation's structure (the ordering, L's pattern, the panels and where the
    // matrix's blocks go in them) from Eigen's factorisation of a matrix of this pattern,
    // diagonally dominant so that it is positive definite.
    const int* outer = matrix.outerIndexPtr();
    const int* inner = matrix.innerIndexPtr();
    for (int col = 0; col < dofs; ++col)
      for (int v = outer[col]; v < outer[col + 1]; ++v)
        matrix.valuePtr()[v] = inner[v] == col ? double(outer[col + 1] - outer[col]) : 1.0;
    const SupernodalLdlt::Factor structure(matrix);
    if (structure.info() != Eigen::Success)
      throw std::logic_error("HandSimulator: no factorisation of the Newton matrix's pattern");
    preconditioner.analyze(structure, matrix);
    find_panel_blocks();
    for (const TetElement& t : m.tets) flesh_tets.push_back({t.nodes, t.volume, t.gradients});
    cube_trailing = preconditioner.trailing(cube_dofs);
  }

  // The value index of (row, col); the rows of a 3x3 block follow it.
  int entry(int row, int col) const {
    const int* rows = matrix.innerIndexPtr();
    const int begin = matrix.outerIndexPtr()[col], end = matrix.outerIndexPtr()[col + 1];
    return int(std::lower_bound(rows + begin, rows + end, row) - rows);
  }

  // The panels' places, once the factorisation has its structure.
  void find_panel_blocks() {
    tet_blocks.clear();
    for (const TetElement& t : model.tets) {
      std::array<PanelBlock, 10> e;
      std::size_t k = 0;
      for (int a = 0; a < 4; ++a)
        for (int b = a; b < 4; ++b)
          e[k++] = panel_block(t.nodes[std::size_t(a)], t.nodes[std::size_t(b)]);
      tet_blocks.push_back(e);
    }
    coupling_blocks.clear();
    for (const SimCoupling& c : model.coupling)
      spring_blocks({c.nodes[0], c.nodes[1], c.nodes[2], c.nodes[3], bone_block(c.bone),
                     bone_block(c.bone) + 1},
                    coupling_blocks);
    joint_blocks.clear();
    for (const SimJoint& j : model.joints)
      spring_blocks({bone_block(j.parent), bone_block(j.parent) + 1, bone_block(j.child),
                     bone_block(j.child) + 1},
                    joint_blocks);
    diagonal_blocks.clear();
    for (int b = 0; b < blocks; ++b) diagonal_blocks.push_back(panel_block(b, b));
    // Two lanes assemble the panels below and from the panel that holds the median of the
    // tets' blocks (most of the assembly's work).
    std::vector<int> places;
    for (const auto& e : tet_blocks)
      for (const PanelBlock& p : e) places.push_back(p.at);
    std::nth_element(places.begin(), places.begin() + std::ptrdiff_t(places.size() / 2),
                     places.end());
    panel_split = places.empty() ? 0 : preconditioner.panel_start(places[places.size() / 2]);
  }

  // Block (bi, bj)'s place; checked to be a 3x3 block of a panel.
  PanelBlock panel_block(int bi, int bj) const {
    const SupernodalLdlt& f = preconditioner;
    PanelBlock p;
    p.transposed = !f.ordered_after(3 * bi, 3 * bj);
    const int row = p.transposed ? 3 * bj : 3 * bi, col = p.transposed ? 3 * bi : 3 * bj;
    p.at = f.position(row, col);
    p.stride = f.column_stride(col);
    // A panel keeps its rows in order: rows row and row + 2 two places apart hold row + 1
    // between them, and column col + 2 where the stride puts it shares the panel.
    if (p.at < 0 || f.position(row + 2, col) != p.at + 2 ||
        f.position(row + 2, col + 2) != p.at + 2 + 2 * p.stride)
      throw std::logic_error("HandSimulator: a 3x3 block split across the panels");
    return p;
  }

  // The places add_spring's `cached` takes for a spring on these blocks: 3x3 of them for each
  // pair, at = -1 where the pair's mirror writes.
  void spring_blocks(const std::vector<int>& point_blocks, std::vector<PanelBlock>& out) const {
    for (int a : point_blocks)
      for (int b : point_blocks)
        out.push_back(a == b || preconditioner.ordered_after(3 * a, 3 * b) ? panel_block(a, b)
                                                                           : PanelBlock{});
  }

  // A term on a diagonal block of the Newton matrix.
  void add_block(int b, const Eigen::Matrix3d& m) {
    if (with_hessian) block_terms.push_back({b, m});
  }

  // The energy 1/2 d'Kd of a point's offset d (K symmetric positive semidefinite): gradient
  // J'Kd, Gauss-Newton Hessian J'KJ. `cached`, when given, holds each block pair's place
  // in the panels (see spring_blocks), so that assembling the fixed springs (coupling, joints)
  // needs no search.
  void add_spring(const PointJacobian& p, const Eigen::Matrix3d& k, const Eigen::Vector3d& d,
                  const PanelBlock* cached = nullptr) {
    const Eigen::Vector3d f = scale * (k * d);
    energy += 0.5 * d.dot(f);
    for (int a = 0; a < p.count; ++a)
      gradient.segment<3>(3 * p.block[std::size_t(a)]) += p.j[std::size_t(a)].transpose() * f;
    if (with_hessian) spring_terms.push_back({p, scale * k, cached});
  }

  // Only the Hessian J'KJ of a spring (no energy or force).
  void add_curvature(const PointJacobian& p, const Eigen::Matrix3d& k) {
    if (with_hessian) spring_terms.push_back({p, scale * k, nullptr});
  }

  // y += (the tets' part of A) x.
  void tet_products(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
    const std::size_t count = flesh_tets.size();
    for (std::size_t k = 0; k < tet_terms.size(); ++k) {
      const TetTerms4& t = tet_terms[k];
      const std::size_t e = kBatch * k;
      Lane4 p[12];  // x at the tets' nodes
      for (int l = 0; l < kBatch; ++l) {
        const auto& ids = flesh_tets[std::min(e + std::size_t(l), count - 1)].nodes;
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < 3; ++i) p[3 * a + i][l] = x[3 * ids[std::size_t(a)] + i];
      }
      // With D = sum_b p_b r_b', the blocks' sum is vmu (D + D') r_a + vlambda tr(D) r_a,
      // and the stiffening's q_a (q . p).
      Lane4 d[9];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          d[3 * i + j] = p[i] * t.rotated[j] + p[3 + i] * t.rotated[3 + j] +
                         p[6 + i] * t.rotated[6 + j] + p[9 + i] * t.rotated[9 + j];
      const Lane4 lambda_trace = t.vlambda * (d[0] + d[4] + d[8]);
      Lane4 stress[9];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) stress[3 * i + j] = t.vmu * (d[3 * i + j] + d[3 * j + i]);
      for (int i = 0; i < 3; ++i) stress[4 * i] += lambda_trace;
      Lane4 qp = Lane4::Zero();
      for (int i = 0; i < 12; ++i) qp += t.q[i] * p[i];
      Lane4 product[12];
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i)
          product[3 * a + i] = stress[3 * i] * t.rotated[3 * a] +
                               stress[3 * i + 1] * t.rotated[3 * a + 1] +
                               stress[3 * i + 2] * t.rotated[3 * a + 2] + t.q[3 * a + i] * qp;
      for (int l = 0; l < kBatch && e + std::size_t(l) < count; ++l) {
        const auto& ids = flesh_tets[e + std::size_t(l)].nodes;
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < 3; ++i) y[3 * ids[std::size_t(a)] + i] += product[3 * a + i][l];
      }
    }
  }

  // y = A x, term by term.
  void multiply(const Eigen::VectorXd& x, Eigen::VectorXd& y) const {
    y.resize(dofs);
    y.tail(dofs - 3 * nodes).setZero();
    for (int n = 0; n < nodes; ++n)
      y.segment<3>(3 * n) = model.node_mass[std::size_t(n)] * x.segment<3>(3 * n);
    tet_products(x, y);
    for (const SpringTerm& t : spring_terms) {
      Eigen::Vector3d u = Eigen::Vector3d::Zero();
      for (int a = 0; a < t.p.count; ++a)
        u += t.p.j[std::size_t(a)] * x.segment<3>(3 * t.p.block[std::size_t(a)]);
      const Eigen::Vector3d v = t.k * u;
      for (int a = 0; a < t.p.count; ++a)
        y.segment<3>(3 * t.p.block[std::size_t(a)]) += t.p.j[std::size_t(a)].transpose() * v;
    }
    for (const BlockTerm& t : block_terms)
      y.segment<3>(3 * t.block) += t.m * x.segment<3>(3 * t.block);
  }

  // The matrix's diagonal, term by term: that of the terms a later pass keeps, found once,
  // and the contacts'.
  Eigen::VectorXd diagonal() const {
    auto add_springs = [&](Eigen::VectorXd& diag, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const SpringTerm& t = spring_terms[i];
        for (int a = 0; a < t.p.count; ++a) {
          const Eigen::Matrix3d& j = t.p.j[std::size_t(a)];
          diag.segment<3>(3 * t.p.block[std::size_t(a)]) += (j.transpose() * t.k * j).diagonal();
        }
      }
    };
    auto add_blocks = [&](Eigen::VectorXd& diag, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i)
        diag.segment<3>(3 * block_terms[i].block) += block_terms[i].m.diagonal();
    };
    if (!base_diagonal_known) {
      Eigen::VectorXd& diag = base_diagonal;
      diag.setZero(dofs);
      for (int n = 0; n < nodes; ++n)
        diag.segment<3>(3 * n).setConstant(model.node_mass[std::size_t(n)]);
      // A tet's diagonal block (a, a) has vmu (|r_a|^2 + r_a[i]^2) + vlambda r_a[i]^2 + q_a[i]^2
      // on its diagonal (tet_block).
      const std::size_t count = flesh_tets.size();
      for (std::size_t k = 0; k < tet_terms.size(); ++k) {
        const TetTerms4& t = tet_terms[k];
        Lane4 d[12];
        for (int a = 0; a < 4; ++a) {
          const Lane4* r = t.rotated + 3 * a;
          const Lane4 length = t.vmu * (r[0].square() + r[1].square() + r[2].square());
          for (int i = 0; i < 3; ++i)
            d[3 * a + i] = length + (t.vmu + t.vlambda) * r[i].square() + t.q[3 * a + i].square();
        }
        for (int l = 0; l < kBatch && kBatch * k + std::size_t(l) < count; ++l) {
          const auto& ids = flesh_tets[kBatch * k + std::size_t(l)].nodes;
          for (int a = 0; a < 4; ++a)
            for (int i = 0; i < 3; ++i) diag[3 * ids[std::size_t(a)] + i] += d[3 * a + i][l];
        }
      }
      add_springs(diag, 0, kept_springs);
      add_blocks(diag, 0, kept_blocks);
      base_diagonal_known = true;
    }
    Eigen::VectorXd diag = base_diagonal;
    add_springs(diag, kept_springs, spring_terms.size());
    add_blocks(diag, kept_blocks, block_terms.size());
    return diag;
  }

  // The part of the matrix's cube-cube block from terms on the cube alone (its inertia, the
  // floor's contacts with its corners), term by term. Of the springs only the contacts' (those
  // after kept_springs) can be on the cube alone.
  bool cube_alone(const SpringTerm& t) const {
    for (int a = 0; a < t.p.count; ++a)
      if (t.p.block[std::size_t(a)] < cube_block()) return false;
    return true;
  }
  Matrix6d cube_matrix() const {
    Matrix6d m = Matrix6d::Zero();
    const int cube = cube_block();
    for (std::size_t i = kept_springs; i < spring_terms.size(); ++i) {
      const SpringTerm& t = spring_terms[i];
      if (!cube_alone(t)) continue;
      for (int a = 0; a < t.p.count; ++a) {
        const int ba = t.p.block[std::size_t(a)] - cube;
        if (ba < 0) continue;
        const Eigen::Matrix3d jk = t.p.j[std::size_t(a)].transpose() * t.k;
        for (int b = 0; b < t.p.count; ++b) {
          const int bb = t.p.block[std::size_t(b)] - cube;
          if (bb >= 0) m.block<3, 3>(3 * ba, 3 * bb) += jk * t.p.j[std::size_t(b)];
        }
      }
    }
    for (const BlockTerm& t : block_terms)
      if (t.block >= cube) m.block<3, 3>(3 * (t.block - cube), 3 * (t.block - cube)) += t.m;
    return m;
  }

  // The contact terms that reach other unknowns than the cube's (into `out`).
  void other_contacts(std::vector<SpringTerm>& out) const {
    out.clear();
    for (std::size_t i = kept_springs; i < spring_terms.size(); ++i)
      if (!cube_alone(spring_terms[i])) out.push_back(spring_terms[i]);
  }
  // Whether those terms equal `known`, bit for bit (the same contacts evaluated at the same
  // state).
  bool same_other_contacts(const std::vector<SpringTerm>& known) const {
    std::size_t k = 0;
    for (std::size_t i = kept_springs; i < spring_terms.size(); ++i) {
      const SpringTerm& t = spring_terms[i];
      if (cube_alone(t)) continue;
      if (k == known.size()) return false;
      const SpringTerm& u = known[k++];
      if (t.p.count != u.p.count || t.p.block != u.p.block || t.k != u.k) return false;
      for (int a = 0; a < t.p.count; ++a)
        if (t.p.j[std::size_t(a)] != u.p.j[std::size_t(a)]) return false;
    }
    return k == known.size();
  }

  // A tet's block (a, b) of the matrix; block (b, a) is its transpose.
  Eigen::Matrix3d tet_block(std::size_t e, int a, int b) const {
    const TetTerms4& t = tet_terms[e / kBatch];
    const int l = int(e % kBatch);
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

  // The matrix as a sparse matrix (the first factorisation's, which finds the structure, and
  // the tests' check_products).
  void assemble() {
    double* values = matrix.valuePtr();
    std::fill(values, values + matrix.nonZeros(), 0.0);
    auto add = [&](int bi, int bj, const Eigen::Matrix3d& m) {
      for (int c = 0; c < 3; ++c) {
        const int column = entry(3 * bi, 3 * bj + c);
        for (int r = 0; r < 3; ++r) values[column + r] += m(r, c);
      }
    };
    for (int n = 0; n < nodes; ++n)
      add(n, n, model.node_mass[std::size_t(n)] * Eigen::Matrix3d::Identity());
    for (std::size_t e = 0; e < flesh_tets.size(); ++e) {
      const auto& ids = flesh_tets[e].nodes;
      for (int a = 0; a < 4; ++a)
        for (int b = a; b < 4; ++b) {
          const Eigen::Matrix3d block = tet_block(e, a, b);
          add(ids[std::size_t(a)], ids[std::size_t(b)], block);
          if (a != b) add(ids[std::size_t(b)], ids[std::size_t(a)], block.transpose());
        }
    }
    for (const SpringTerm& t : spring_terms) {
      const PointJacobian& p = t.p;
      for (int a = 0; a < p.count; ++a)
        for (int b = 0; b < p.count; ++b)
          add(p.block[std::size_t(a)], p.block[std::size_t(b)],
              p.j[std::size_t(a)].transpose() * t.k * p.j[std::size_t(b)]);
    }
    for (const BlockTerm& t : block_terms) add(t.block, t.block, t.m);
  }

  // The matrix added straight into the factorisation's panel values (the lower triangle after
  // its ordering; SupernodalLdlt::position), for a factorisation: `values` is the
  // factorisation's own (cleared), or for the tests a copy. With `lane` 0 or 1, only the
  // blocks below or from panel_split: two lanes write disjoint values, each in the order the
  // serial assembly adds them, so that the sums are the same bit for bit.
  void assemble_panels(double* values, int lane = -1) const {
    auto owns = [&](int at) { return lane < 0 || (at >= panel_split) == (lane == 1); };
    auto add = [values](const PanelBlock& p, const Eigen::Matrix3d& m) {
      double* v = values + p.at;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) v[r + p.stride * c] += p.transposed ? m(c, r) : m(r, c);
    };
    auto add_diagonal = [values](const PanelBlock& p, const Eigen::Matrix3d& m) {
      double* v = values + p.at;
      for (int c = 0; c < 3; ++c)
        for (int r = c; r < 3; ++r) v[r + p.stride * c] += m(r, c);
    };
    for (int n = 0; n < nodes; ++n) {
      const PanelBlock& p = diagonal_blocks[std::size_t(n)];
      if (!owns(p.at)) continue;
      for (int c = 0; c < 3; ++c)
        values[p.at + (p.stride + 1) * c] += model.node_mass[std::size_t(n)];
    }
    const std::size_t count = flesh_tets.size();
    for (std::size_t k = 0; k < tet_terms.size(); ++k) {
      const TetTerms4& t = tet_terms[k];
      // Block (a, b) of the four tets, entry (r, c) at 9 n + r + 3 c for the n-th pair a <= b
      // (as tet_block): vmu r_b[r] r_a[c] + vlambda r_a[r] r_b[c] + q_a[r] q_b[c], and
      // vmu r_a . r_b on its diagonal.
      Lane4 block[90];
      int n = 0;
      for (int a = 0; a < 4; ++a)
        for (int b = a; b < 4; ++b, ++n) {
          const Lane4* ra = t.rotated + 3 * a;
          const Lane4* rb = t.rotated + 3 * b;
          const Lane4 diagonal = t.vmu * (ra[0] * rb[0] + ra[1] * rb[1] + ra[2] * rb[2]);
          for (int c = 0; c < 3; ++c) {
            const Lane4 mu_c = t.vmu * ra[c], lambda_c = t.vlambda * rb[c];
            for (int r = 0; r < 3; ++r)
              block[9 * n + r + 3 * c] = mu_c * rb[r] + lambda_c * ra[r] +
                                         t.q[3 * a + r] * t.q[3 * b + c] +
                                         (r == c ? diagonal : Lane4::Zero());
          }
        }
      // Into each tet's places, as the block or, where the panels hold the mirror, its
      // transpose (a diagonal block's lower triangle only).
      for (int l = 0; l < kBatch && kBatch * k + std::size_t(l) < count; ++l) {
        const auto& places = tet_blocks[kBatch * k + std::size_t(l)];
        n = 0;
        for (int a = 0; a < 4; ++a)
          for (int b = a; b < 4; ++b, ++n) {
            const PanelBlock& place = places[std::size_t(n)];
            if (!owns(place.at)) continue;
            double* v = values + place.at;
            const Lane4* m = block + 9 * n;
            if (a == b) {
              for (int c = 0; c < 3; ++c)
                for (int r = c; r < 3; ++r) v[place.stride * c + r] += m[r + 3 * c][l];
            } else if (place.transposed) {
              for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r) v[place.stride * c + r] += m[c + 3 * r][l];
            } else {
              for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r) v[place.stride * c + r] += m[r + 3 * c][l];
            }
          }
      }
    }
    for (const SpringTerm& t : spring_terms) {
      const PointJacobian& p = t.p;
      for (int a = 0; a < p.count; ++a) {
        const Eigen::Matrix3d jk = p.j[std::size_t(a)].transpose() * t.k;
        for (int b = 0; b < p.count; ++b) {
          const int ba = p.block[std::size_t(a)], bb = p.block[std::size_t(b)];
          PanelBlock place;
          if (t.cached)
            place = t.cached[p.count * a + b];
          else if (ba == bb || preconditioner.ordered_after(3 * ba, 3 * bb))
            place = panel_block(ba, bb);
          if (place.at < 0 || !owns(place.at)) continue;  // its mirror (b, a) writes it
          const Eigen::Matrix3d block = jk * p.j[std::size_t(b)];
          if (ba == bb)
            add_diagonal(place, block);
          else
            add(place, block);
        }
      }
    }
    for (const BlockTerm& t : block_terms)
      if (owns(diagonal_blocks[std::size_t(t.block)].at))
        add_diagonal(diagonal_blocks[std::size_t(t.block)], t.m);
  }

  // A constant force -f on a point at `position` (the energy f . position).
  void add_force(const PointJacobian& p, const Eigen::Vector3d& f,
                 const Eigen::Vector3d& position) {
    energy += scale * f.dot(position);
    for (int a = 0; a < p.count; ++a)
      gradient.segment<3>(3 * p.block[std::size_t(a)]) +=
          scale * p.j[std::size_t(a)].transpose() * f;
  }

  void add_body_point(PointJacobian& p, int block, const Eigen::Vector3d& arm, double sign) const {
    p.add(block, sign * Eigen::Matrix3d::Identity());
    p.add(block + 1, -sign * cross_matrix(arm));  // d(c + r) = dc + dtheta x r
  }

  // Linear co-rotational flesh with the stiffening term, per tet: F from the edge vectors, R
  // (extracted where Newton linearises, held in its line search), the strain e = sym(R'F) - I,
  // the stress s = 2 mu e + lambda tr(e) I, node forces V R s grad N_a, and the Hessian
  // R K R' assembled from the rotated shape gradients without forming 12x12 products.
  // The tets split over the lanes, each lane's forces into its own buffer (lane 0's into the
  // gradient), added in lane order. Without the Hessian (the line search), the energy alone.
  void flesh(HandSimState& s) {
    const int count = int(flesh_tets.size()), batches = (count + kBatch - 1) / kBatch;
    if (with_hessian) tet_terms.resize(std::size_t(batches));
    lanes.run([&](int lane) {
      // Whole batches to each lane.
      const auto [first, last] = lanes.range(lane, batches);
      const int begin = std::min(kBatch * first, count), end = std::min(kBatch * last, count);
      double* forces = gradient.data();
      if (lane > 0 && with_hessian) {
        lane_forces[std::size_t(lane)].setZero(3 * nodes);
        forces = lane_forces[std::size_t(lane)].data();
      }
      lane_energy[std::size_t(lane)] =
          with_hessian ? flesh_range(s, std::size_t(begin), std::size_t(end), forces)
                       : flesh_energy(s, std::size_t(begin), std::size_t(end));
    });
    for (int lane = 0; lane < lanes.count(); ++lane) {
      energy += lane_energy[std::size_t(lane)];
      if (lane > 0 && with_hessian) gradient.head(3 * nodes) += lane_forces[std::size_t(lane)];
    }
  }

  // The flesh four tets at a time, one in each lane of Eigen's 4-wide arrays (the vector
  // unit's), the lanes' energies summed at the end. A batch past the range's end repeats its
  // last tet with no volume.
  struct TetBatch {
    Lane4 f[9];           // F, row-major
    Lane4 r[9];           // R, row-major
    Lane4 gradients[12];  // grad N_a, entry 3a + i
    Lane4 volume;
  };

  // F of tets e, ... (sum over a of (x_a - x_0) grad N_a').
  void gather(const HandSimState& s, std::size_t e, std::size_t end, TetBatch& b,
              bool with_gradients) const {
    for (Lane4& v : b.f) v.setZero();
    for (int l = 0; l < kBatch; ++l) {
      const std::size_t k = std::min(e + std::size_t(l), end - 1);
      const FleshTet& t = flesh_tets[k];
      const Eigen::Vector3d& x0 = s.node_position[std::size_t(t.nodes[0])];
      for (int a = 1; a < 4; ++a) {
        const Eigen::Vector3d d = s.node_position[std::size_t(t.nodes[std::size_t(a)])] - x0;
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) b.f[3 * i + j][l] += d[i] * t.gradients(j, a);
      }
      b.volume[l] = e + std::size_t(l) < end ? t.volume : 0.0;
      if (with_gradients)
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < 3; ++i) b.gradients[3 * a + i][l] = t.gradients(i, a);
    }
  }

  // R of tets e, ... from their quaternions.
  void rotations(const HandSimState& s, std::size_t e, std::size_t end, TetBatch& b) const {
    Lane4 w, x, y, z;
    for (int l = 0; l < kBatch; ++l) {
      const Eigen::Quaterniond& q = s.tet_rotation[std::min(e + std::size_t(l), end - 1)];
      w[l] = q.w();
      x[l] = q.x();
      y[l] = q.y();
      z[l] = q.z();
    }
    rotation_matrices(w, x, y, z, b.r);
  }

  // The strain sym(R'F) - I (xx, yy, zz, xy, xz, yz).
  static void strain(const TetBatch& b, Lane4 (&e)[6]) {
    auto g = [&](int i, int j) {  // (R'F)_ij
      return b.r[i] * b.f[j] + b.r[3 + i] * b.f[3 + j] + b.r[6 + i] * b.f[6 + j];
    };
    e[0] = g(0, 0) - 1;
    e[1] = g(1, 1) - 1;
    e[2] = g(2, 2) - 1;
    e[3] = 0.5 * (g(0, 1) + g(1, 0));
    e[4] = 0.5 * (g(0, 2) + g(2, 0));
    e[5] = 0.5 * (g(1, 2) + g(2, 1));
  }
  static Lane4 squared_norm(const Lane4 (&e)[6]) {
    return e[0].square() + e[1].square() + e[2].square() +
           2 * (e[3].square() + e[4].square() + e[5].square());
  }

  // The energy of tets [begin, end) alone (the line search's), with their rotations as the
  // last evaluation with the Hessian found them.
  double flesh_energy(const HandSimState& s, std::size_t begin, std::size_t end) const {
    const SimParameters& par = model.parameters;
    const double mu = par.flesh.mu(), lambda = par.flesh.lambda();
    const double stiffening = par.stiffening_factor * par.flesh.youngs_modulus;
    Lane4 sum = Lane4::Zero();
    TetBatch b;
    for (std::size_t e = begin; e < end; e += kBatch) {
      gather(s, e, end, b, false);
      rotations(s, e, end, b);
      Lane4 n[6];
      strain(b, n);
      const Lane4 trace = n[0] + n[1] + n[2], squared = squared_norm(n);
      const Lane4 excess = (squared.sqrt() - par.stiffening_strain).max(0.0);
      sum += b.volume *
             (mu * squared + 0.5 * lambda * trace.square() + 0.5 * stiffening * excess.square());
    }
    return scale * ((sum[0] + sum[1]) + (sum[2] + sum[3]));
  }

  // Tets [begin, end): their rotations (polar decomposition of F, from the last), their
  // energy, their forces added to `forces` (node DOFs), their Hessian terms.
  double flesh_range(HandSimState& s, std::size_t begin, std::size_t end, double* forces) {
    const SimParameters& par = model.parameters;
    const double mu = par.flesh.mu(), lambda = par.flesh.lambda();
    const double stiffening = par.stiffening_factor * par.flesh.youngs_modulus;
    const double threshold = par.stiffening_strain;
    Lane4 sum = Lane4::Zero();
    TetBatch b;
    for (std::size_t e = begin; e < end; e += kBatch) {
      gather(s, e, end, b, true);
      const int count = int(std::min<std::size_t>(kBatch, end - e));
      Eigen::Quaterniond* const q[kBatch] = {
          &s.tet_rotation[e], &s.tet_rotation[e + std::size_t(std::min(1, count - 1))],
          &s.tet_rotation[e + std::size_t(std::min(2, count - 1))],
          &s.tet_rotation[e + std::size_t(std::min(3, count - 1))]};
      extract_rotations(b.f, q, count);
      rotations(s, e, end, b);
      Lane4 n[6];
      strain(b, n);
      const Lane4 trace = n[0] + n[1] + n[2], squared = squared_norm(n), norm = squared.sqrt();
      // Stiffening beyond a strain threshold: (k V / 2)(|e| - e0)^2, whose stress is
      // k (|e| - e0) e / |e|; its Hessian k V [(e0/|e|) q q' + (1 - e0/|e|) B'B] (q the
      // gradient direction, B the strain map) is positive semidefinite.
      const auto stiff = norm > threshold;
      const Lane4 excess = stiff.select(norm - threshold, 0.0);
      const Lane4 safe_norm = stiff.select(norm, 1.0);
      const Lane4 ratio = stiff.select(threshold / safe_norm, 1.0);
      const Lane4 k = stiff.select(stiffening * b.volume, 0.0);
      sum += b.volume * (mu * squared + 0.5 * lambda * trace.square()) + 0.5 * k * excess.square();
      // stress = 2 mu e + lambda tr(e) I + (stiffening excess / |e|) e, row-major.
      const Lane4 shear = 2 * mu + stiffening * excess / safe_norm;
      const Lane4 stress[9] = {
          shear * n[0] + lambda * trace, shear * n[3], shear * n[4], shear * n[3],
          shear * n[1] + lambda * trace, shear * n[5], shear * n[4], shear * n[5],
          shear * n[2] + lambda * trace};
      const Lane4 e9[9] = {n[0], n[3], n[4], n[3], n[1], n[5], n[4], n[5], n[2]};
      // R stress and R e, row-major.
      Lane4 rs[9], re[9];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          rs[3 * i + j] = b.r[3 * i] * stress[j] + b.r[3 * i + 1] * stress[3 + j] +
                          b.r[3 * i + 2] * stress[6 + j];
          re[3 * i + j] =
              b.r[3 * i] * e9[j] + b.r[3 * i + 1] * e9[3 + j] + b.r[3 * i + 2] * e9[6 + j];
        }
      const Lane4 q_scale = stiff.select((scale * k * ratio).sqrt() / safe_norm, 0.0);
      const Lane4 force_scale = scale * b.volume;
      // The terms (a batch past the last tet has no volume: no terms).
      TetTerms4& term = tet_terms[e / kBatch];
      term.vmu = scale * (b.volume * mu + 0.5 * k * (1.0 - ratio));
      term.vlambda = scale * b.volume * lambda;
      // Times grad N_a: the forces, R grad N_a and the stiffening's rank-one part.
      Lane4 force[12];
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) {
          const Lane4 &g0 = b.gradients[3 * a], &g1 = b.gradients[3 * a + 1],
                      &g2 = b.gradients[3 * a + 2];
          force[3 * a + i] =
              force_scale * (rs[3 * i] * g0 + rs[3 * i + 1] * g1 + rs[3 * i + 2] * g2);
          term.rotated[3 * a + i] = b.r[3 * i] * g0 + b.r[3 * i + 1] * g1 + b.r[3 * i + 2] * g2;
          term.q[3 * a + i] = q_scale * (re[3 * i] * g0 + re[3 * i + 1] * g1 + re[3 * i + 2] * g2);
        }
      for (int l = 0; l < count; ++l) {
        const FleshTet& t = flesh_tets[e + std::size_t(l)];
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < 3; ++i)
            forces[3 * t.nodes[std::size_t(a)] + i] += force[3 * a + i][l];
      }
    }
    return scale * ((sum[0] + sum[1]) + (sum[2] + sum[3]));
  }

  void bodies(const HandSimState& s, const std::vector<RigidPose>& targets) {
    const SimParameters& par = model.parameters;
    const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
    for (std::size_t i = 0; i < model.coupling.size(); ++i) {
      const SimCoupling& c = model.coupling[i];
      const RigidPose& bone = s.bone_pose[std::size_t(c.bone)];
      const Eigen::Vector3d arm = bone.rotation * c.in_bone;
      Eigen::Vector3d flesh_point = Eigen::Vector3d::Zero();
      for (int a = 0; a < 4; ++a)
        flesh_point += c.weights(a) * s.node_position[std::size_t(c.nodes[std::size_t(a)])];
      if (!with_hessian) {  // the line search: add_spring's energy alone, as it computes it
        const Eigen::Vector3d d = flesh_point - bone.position - arm;
        energy += 0.5 * d.dot(scale * (c.stiffness * d));
        continue;
      }
      PointJacobian p;
      for (int a = 0; a < 4; ++a) p.add(c.nodes[std::size_t(a)], c.weights(a) * identity);
      add_body_point(p, bone_block(c.bone), arm, -1.0);
      add_spring(p, c.stiffness * identity, flesh_point - bone.position - arm,
                 coupling_blocks.empty() ? nullptr : coupling_blocks.data() + 36 * i);
    }
    for (std::size_t i = 0; i < model.joints.size(); ++i) {
      const SimJoint& j = model.joints[i];
      const RigidPose &parent = s.bone_pose[std::size_t(j.parent)],
                      &child = s.bone_pose[std::size_t(j.child)];
      const Eigen::Vector3d arm_p = parent.rotation * j.in_parent,
                            arm_c = child.rotation * j.in_child;
      PointJacobian p;
      add_body_point(p, bone_block(j.parent), arm_p, 1.0);
      add_body_point(p, bone_block(j.child), arm_c, -1.0);
      add_spring(p, par.joint_stiffness * identity,
                 parent.position + arm_p - child.position - arm_c,
                 joint_blocks.empty() ? nullptr : joint_blocks.data() + 16 * i);
    }
    for (int b = 0; b < bones; ++b) {
      const RigidPose& pose = s.bone_pose[std::size_t(b)];
      const RigidPose& target = targets[std::size_t(b)];
      // Tracking: the centre of mass towards the target's, and the rotation by the rotation
      // vector that separates them (its derivative is the identity near the target).
      const int tb = bone_block(b);
      PointJacobian centre;
      centre.add(tb, identity);
      add_spring(centre, par.tracking_stiffness * identity, pose.position - target.position);
      const Eigen::Vector3d phi = rotation_vector(pose.rotation * target.rotation.conjugate());
      energy += 0.5 * scale * par.tracking_torsion * phi.squaredNorm();
      gradient.segment<3>(3 * (tb + 1)) += scale * par.tracking_torsion * phi;
      add_block(tb + 1, scale * par.tracking_torsion * identity);
      const double mass = model.bones[std::size_t(b)].inertia.mass;
      energy -= scale * mass * par.gravity.dot(pose.position);
      gradient.segment<3>(3 * tb) -= scale * mass * par.gravity;
    }
    energy -= scale * model.cube.mass * par.gravity.dot(s.cube_pose.position);
    gradient.segment<3>(3 * cube_block()) -= scale * model.cube.mass * par.gravity;
    for (int n = 0; n < nodes; ++n) {
      const double mass = model.node_mass[std::size_t(n)];
      energy -= scale * mass * par.gravity.dot(s.node_position[std::size_t(n)]);
      gradient.segment<3>(3 * n) -= scale * mass * par.gravity;
    }
  }

  // The normal penalty's stiffness at the surface (and the friction spring's).
  double stiffness(const Contact& c) const {
    return c.kind == Contact::kCornerFloor ? model.parameters.cube_floor_stiffness
                                           : model.parameters.contact_stiffness;
  }
  // Its growth with depth: a flesh node's penalty force is k d + k3 d^2 (soft where the skin
  // first touches, so that the pad takes a light cube on several nodes; stiff deeper in, so
  // that a heavy one does not sink).
  double stiffening(const Contact& c) const {
    return c.kind == Contact::kCornerFloor ? 0.0 : model.parameters.contact_stiffening;
  }
  // The friction cone's radius about the anchor at a depth: mu f_n / k.
  double cone(const Contact& c, double depth) const {
    depth = std::max(depth, 0.0);
    return model.parameters.friction * depth * (1.0 + stiffening(c) * depth / stiffness(c));
  }

  // The normal penalty of a point at a signed distance < 0 from a surface of outward normal n:
  // the energy k d^2/2 + k3 d^3/3 of the depth d, its force (k d + k3 d^2) n, its curvature
  // (k + 2 k3 d) n n'.
  void add_penalty(const PointJacobian& p, const Eigen::Vector3d& n, double distance, double k,
                   double k3) {
    const double d = -distance;
    energy += scale * d * d * (0.5 * k + k3 * d / 3.0);
    const Eigen::Vector3d f = (scale * (k + k3 * d) * distance) * n;
    for (int a = 0; a < p.count; ++a)
      gradient.segment<3>(3 * p.block[std::size_t(a)]) += p.j[std::size_t(a)].transpose() * f;
    add_curvature(p, (k + 2.0 * k3 * d) * n * n.transpose());
  }

  // Contact energies at the state: the normal penalty (add_penalty) wherever the point is inside
  // (the exact distance, so that a point passing beside an edge feels nothing), friction as
  // decided at the predicted state.
  void contact_energies(const HandSimState& s) {
    const SimParameters& par = model.parameters;
    const Eigen::Vector3d nf = par.floor_normal.normalized();
    const Eigen::Matrix3d cube_r = s.cube_pose.rotation.toRotationMatrix();
    const Eigen::Matrix3d identity = Eigen::Matrix3d::Identity();
    for (const Contact& c : contacts) {
      const double k = stiffness(c);
      PointJacobian p;
      Eigen::Vector3d x;
      if (c.kind == Contact::kCornerFloor) {
        const Eigen::Vector3d arm =
            cube_r * corner_signs()[std::size_t(c.point)].cwiseProduct(model.cube_half);
        x = s.cube_pose.position + arm;
        add_body_point(p, cube_block(), arm, 1.0);
      } else {
        x = s.node_position[std::size_t(c.point)];
        p.add(c.point, identity);
      }
      if (c.kind != Contact::kNodeCube) {
        const double height = nf.dot(x) - par.floor_height;
        if (height < 0)
          add_penalty(p, nf, height, k, stiffening(c));
        else if (c.curved)
          add_curvature(p, k * nf * nf.transpose());
        if (!c.touching || height >= 0) continue;  // no friction from a point that left
        if (c.sliding)
          add_force(p, c.friction_force * c.slip, x);
        else
          add_spring(p, k * (identity - c.normal * c.normal.transpose()), x - c.anchor);
        continue;
      }
      // Against the cube: the surface point and the anchor move with it.
      const BoxProximity b = box_proximity(
          model.cube_half, s.cube_pose.rotation.conjugate() * (x - s.cube_pose.position));
      if (b.distance < 0 || c.curved) {
        const Eigen::Vector3d n = cube_r * b.normal, surface = s.cube_pose.point(b.closest);
        PointJacobian normal_part = p;
        add_body_point(normal_part, cube_block(), surface - s.cube_pose.position, -1.0);
        if (b.distance < 0)
          add_penalty(normal_part, n, b.distance, k, stiffening(c));
        else
          add_curvature(normal_part, k * n * n.transpose());
      }
      if (!c.touching || b.distance >= 0) continue;  // no pull from a point that left
      const Eigen::Vector3d anchor = s.cube_pose.point(c.anchor), &n = c.across;
      PointJacobian friction_part = p;
      add_body_point(friction_part, cube_block(), anchor - s.cube_pose.position, -1.0);
      if (c.sliding)
        add_force(friction_part, c.friction_force * (cube_r * c.slip), x - anchor);
      else
        add_spring(friction_part, k * (identity - n * n.transpose()), x - anchor);
    }
  }

  // Contact candidates at the predicted state: every point within a margin of a surface that
  // covers what the bodies can move in a step. Those inside it take friction: their anchor
  // (from the step before, or where they entered) sticks, or, if the predicted state pulls it
  // out of Coulomb's cone, they slide.
  void find_contacts(const HandSimState& s) {
    const SimParameters& par = model.parameters;
    const double h = par.time_step;
    contacts.clear();
    const Eigen::Vector3d nf = par.floor_normal.normalized();
    auto previous = [](const std::vector<ContactAnchor>& list, int point) -> const ContactAnchor* {
      const auto it = std::lower_bound(list.begin(), list.end(), point,
                                       [](const ContactAnchor& a, int p) { return a.point < p; });
      return it != list.end() && it->point == point ? &*it : nullptr;
    };
    // `x` and `surface` in the surface's frame, `gap` the signed distance.
    auto add = [&](Contact::Kind kind, int point, const Eigen::Vector3d& x,
                   const Eigen::Vector3d& normal, const Eigen::Vector3d& surface, double gap,
                   const ContactAnchor* old, double k) {
      Contact c{kind, point, normal, old ? old->anchor : surface};
      c.across = kind == Contact::kNodeCube ? s.cube_pose.rotation * normal : normal;
      c.touching = gap < 0;
      c.curved = c.touching;
      if (c.touching && old) {
        const Eigen::Vector3d t =
            (Eigen::Matrix3d::Identity() - normal * normal.transpose()) * (x - old->anchor);
        const double stretch = t.norm(), limit = cone(c, -gap);
        if (stretch > limit) {
          if (kind == Contact::kNodeCube) {
            // Flesh on the cube keeps an anchor spring, its anchor moved to the cone's edge: a
            // constant kinetic force, fixed for the step, set the light cube ringing when a
            // node's slip reversed within it (measured: a soft block resting on the cube).
            c.anchor = old->anchor + t * (1.0 - limit / stretch);
          } else {
            // Sliding: the anchor stays where the point held, in case the slide stops.
            c.sliding = true;
            c.slip = t / stretch;
            c.friction_force = k * limit;
          }
        }
      }
      contacts.push_back(c);
    };
    const double cube_speed =
        s.cube_velocity.linear.norm() + s.cube_velocity.angular.norm() * model.cube_half.norm();
    const Eigen::Quaterniond cube_inv = s.cube_pose.rotation.conjugate();
    for (int node : model.surface_nodes) {
      const Eigen::Vector3d& x = s.node_position[std::size_t(node)];
      const double speed = s.node_velocity[std::size_t(node)].norm();
      const Eigen::Vector3d q = cube_inv * (x - s.cube_pose.position);
      const BoxProximity b = box_proximity(model.cube_half, q);
      if (b.distance < kContactMargin + 2 * h * (speed + cube_speed))
        add(Contact::kNodeCube, node, q, b.normal, b.closest, b.distance,
            previous(s.node_cube, node), par.contact_stiffness);
      if (par.hand_floor_contact) {
        const double height = nf.dot(x) - par.floor_height;
        if (height < kContactMargin + 2 * h * speed)
          add(Contact::kNodeFloor, node, x, nf, x - height * nf, height,
              previous(s.node_floor, node), par.contact_stiffness);
      }
    }
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d x =
          s.cube_pose.point(corner_signs()[std::size_t(k)].cwiseProduct(model.cube_half));
      const double height = nf.dot(x) - par.floor_height;
      if (height < kContactMargin + 2 * h * cube_speed)
        add(Contact::kCornerFloor, k, x, nf, x - height * nf, height, previous(s.corner_floor, k),
            par.cube_floor_stiffness);
    }
  }

  // Contacts whose curvature the solve left out but whose point ended inside the surface:
  // they take it in the next pass (it is never taken out again, so that passes end).
  bool contacts_entered(const HandSimState& s) {
    const SimParameters& par = model.parameters;
    const Eigen::Vector3d nf = par.floor_normal.normalized();
    const Eigen::Quaterniond cube_inv = s.cube_pose.rotation.conjugate();
    bool entered = false;
    for (Contact& c : contacts) {
      if (c.curved) continue;
      double gap;
      if (c.kind == Contact::kNodeCube) {
        gap = box_proximity(model.cube_half, cube_inv * (s.node_position[std::size_t(c.point)] -
                                                         s.cube_pose.position))
                  .distance;
      } else {
        const Eigen::Vector3d x =
            c.kind == Contact::kNodeFloor
                ? s.node_position[std::size_t(c.point)]
                : s.cube_pose.point(
                      corner_signs()[std::size_t(c.point)].cwiseProduct(model.cube_half));
        gap = nf.dot(x) - par.floor_height;
      }
      if (gap < 0) c.curved = entered = true;
    }
    return entered;
  }

  // Coulomb at the step's result: a sliding contact whose point stopped short of the cone's
  // edge (its slip would reverse) sticks; a sticking one whose spring left the cone slides.
  // True when some contact changed (each may change twice a step and then sticks, so that
  // passes end).
  bool friction_changed(const HandSimState& s) {
    const SimParameters& par = model.parameters;
    const Eigen::Vector3d nf = par.floor_normal.normalized();
    bool changed = false;
    for (Contact& c : contacts) {
      if (!c.touching || c.kind == Contact::kNodeCube) continue;
      if (c.switches >= 2) {
        // A contact that keeps switching ends sticking: the anchor spring is conservative,
        // a kinetic force that disagrees with the motion is not.
        if (c.sliding) {
          c.sliding = false;
          ++c.switches;
          changed = true;
        }
        continue;
      }
      // Only floor contacts are left here (flesh on the floor, cube corners on the floor).
      const Eigen::Vector3d x =
          c.kind == Contact::kNodeFloor
              ? s.node_position[std::size_t(c.point)]
              : s.cube_pose.point(
                    corner_signs()[std::size_t(c.point)].cwiseProduct(model.cube_half));
      const double depth = par.floor_height - nf.dot(x);
      if (depth <= 0) continue;  // left the surface: it felt no friction
      const Eigen::Vector3d offset =
          (Eigen::Matrix3d::Identity() - c.normal * c.normal.transpose()) * (x - c.anchor);
      const double limit = cone(c, depth);
      if (c.sliding && offset.dot(c.slip) <= 0) {
        // The kinetic force turned the slide back past where the point held: it stops there.
        c.sliding = false;
      } else if (c.sliding &&
                 std::abs(stiffness(c) * limit - c.friction_force) > 0.25 * c.friction_force) {
        // Coulomb's force follows the normal force at the result, not at the prediction (a
        // corner predicted deep that bounced out must not take the friction of the depth).
        // Not a switch: the passes' limit ends these updates.
        c.friction_force = stiffness(c) * limit;
        changed = true;
        continue;
      } else if (!c.sliding && offset.norm() > 1.01 * limit) {
        c.sliding = true;
        c.slip = offset.normalized();
        c.friction_force = stiffness(c) * limit;
      } else {
        continue;
      }
      ++c.switches;
      changed = true;
    }
    return changed;
  }

  // After the step: contacts that separated let go of their anchors; the others stick, or
  // slide to the edge of the friction cone (|f_t| = mu f_n).
  void update_anchors(HandSimState& s, double& max_penetration) const {
    const SimParameters& par = model.parameters;
    const Eigen::Vector3d nf = par.floor_normal.normalized();
    s.node_cube.clear();
    s.node_floor.clear();
    s.corner_floor.clear();
    max_penetration = 0.0;
    const Eigen::Quaterniond cube_inv = s.cube_pose.rotation.conjugate();
    for (const Contact& c : contacts) {
      if (c.kind == Contact::kNodeCube) {
        const Eigen::Vector3d q =
            cube_inv * (s.node_position[std::size_t(c.point)] - s.cube_pose.position);
        const BoxProximity b = box_proximity(model.cube_half, q);
        if (b.distance >= 0) continue;
        max_penetration = std::max(max_penetration, -b.distance);
        s.node_cube.push_back({c.point, coulomb_anchor(q, b.normal, cone(c, -b.distance),
                                                       c.touching ? c.anchor : b.closest)});
        continue;
      }
      const Eigen::Vector3d x =
          c.kind == Contact::kNodeFloor
              ? s.node_position[std::size_t(c.point)]
              : s.cube_pose.point(
                    corner_signs()[std::size_t(c.point)].cwiseProduct(model.cube_half));
      const double height = nf.dot(x) - par.floor_height;
      if (height >= 0) continue;
      (c.kind == Contact::kNodeFloor ? s.node_floor : s.corner_floor)
          .push_back({c.point, coulomb_anchor(x, nf, cone(c, -height),
                                              c.touching ? c.anchor : x - height * nf)});
    }
  }

  // h^2 times the backward-Euler energy at `s`, and with `hessian` its gradient and
  // Gauss-Newton Hessian (without, as the line search needs, the energy alone), with `turned`
  // the bodies' rotation vectors since the step began.
  // `reuse`: kKeep keeps every term but the contacts' (energy, forces and Hessian terms: the
  // flesh's, the bodies', the kinetic ones); kKept takes them from the last kKeep, for the state
  // it was at, its tets' rotations as that evaluation found them (a step's later passes start
  // where its first did, and only their contacts differ).
  enum class Reuse { kNone, kKeep, kKept };
  double evaluate(HandSimState& s, const std::vector<Eigen::Vector3d>& turned,
                  const StepFrame& frame, bool hessian, Reuse reuse = Reuse::kNone) {
    with_hessian = hessian;
    if (reuse == Reuse::kKept) {
      gradient = kept_gradient;
      energy = kept_energy;
      spring_terms.resize(kept_springs);
      block_terms.resize(kept_blocks);
    } else {
      energy = 0.0;
      gradient.setZero(dofs);
      if (hessian) {
        spring_terms.clear();
        block_terms.clear();
        base_diagonal_known = false;
        ++terms_found;
      }
      // The tets' rotations are found where Newton linearises and held through its line
      // search: there the flesh energy is the quadratic that the Hessian describes.
      flesh(s);
      if (options.check_products && hessian) check_flesh_gradient(s);
      bodies(s, *frame.targets);
      kinetic_energies(s, turned, *frame.start);
      if (hessian) {
        kept_springs = spring_terms.size();
        kept_blocks = block_terms.size();
      }
      if (reuse == Reuse::kKeep) {
        kept_gradient = gradient;
        kept_energy = energy;
      }
    }
    contact_energies(s);
    return energy;
  }

  // Kinetic terms: 1/2 |q - q_pred|^2_M, the rotations' inertia in the world at the start.
  void kinetic_energies(const HandSimState& s, const std::vector<Eigen::Vector3d>& turned,
                        const HandSimState& start) {
    const HandSimModel& m = model;
    const double h = m.parameters.time_step;
    for (int n = 0; n < nodes; ++n) {
      const double mass = m.node_mass[std::size_t(n)];
      const Eigen::Vector3d d = s.node_position[std::size_t(n)] -
                                start.node_position[std::size_t(n)] -
                                h * start.node_velocity[std::size_t(n)];
      energy += 0.5 * mass * d.squaredNorm();
      if (with_hessian) gradient.segment<3>(3 * n) += mass * d;  // its Hessian is the model's
    }
    auto kinetic = [&](int block, const RigidInertia& inertia, const RigidPose& pose,
                       const RigidPose& from, const RigidVelocity& v,
                       const Eigen::Vector3d& rotated) {
      const Eigen::Vector3d d = pose.position - from.position - h * v.linear;
      energy += 0.5 * inertia.mass * d.squaredNorm();
      gradient.segment<3>(3 * block) += inertia.mass * d;
      add_block(block, inertia.mass * Eigen::Matrix3d::Identity());
      const Eigen::Matrix3d r = from.rotation.toRotationMatrix();
      const Eigen::Matrix3d world = r * inertia.inertia * r.transpose();
      const Eigen::Vector3d a = rotated - h * v.angular;
      energy += 0.5 * a.dot(world * a);
      gradient.segment<3>(3 * (block + 1)) += world * a;
      add_block(block + 1, world);
    };
    for (int b = 0; b < bones; ++b)
      kinetic(bone_block(b), m.bones[std::size_t(b)].inertia, s.bone_pose[std::size_t(b)],
              start.bone_pose[std::size_t(b)], start.bone_velocity[std::size_t(b)],
              turned[std::size_t(b)]);
    kinetic(cube_block(), m.cube, s.cube_pose, start.cube_pose, start.cube_velocity, turned.back());
  }

  // The Newton increment: preconditioned conjugate gradients on the current Hessian with the
  // factorisation of an earlier one (the step's matrix changes slowly: element rotations,
  // contacts that come and go), factorised anew when CG needs more than a few iterations.
  // Measured on the study hand (docs/performance.md), one thread: assembling and factorising
  // cost 2-2.8 ms, a CG iteration (a product term by term and a panel solve) 0.25 ms.
  Eigen::VectorXd solve(SimStepReport& report) {
    const Eigen::VectorXd b = -gradient;
    auto refactor = [&] {
      double* values = preconditioner.values();
      if (lanes.count() >= 2 && panel_split > 0) {
        lanes.run([&](int lane) {
          if (lane > 1) return;
          const int begin = lane == 0 ? 0 : panel_split;
          const int end = lane == 0 ? panel_split : preconditioner.value_count();
          std::fill(values + begin, values + end, 0.0);
          assemble_panels(values, lane);
        });
      } else {
        preconditioner.clear_values();
        assemble_panels(values);
      }
      const bool definite = preconditioner.factorize_values(&lanes);
      if (!definite)
        throw std::runtime_error("HandSimulator: the Newton system is not positive definite");
      factorised = true;
      cube_factorised = cube_matrix();
      cube_applied.setZero();
      factorised_terms = terms_found;
      other_contacts(factorised_contacts);
      factorised_at = step_index;
      slow_steps = 0;
      ++report.factorizations;
    };
    // A direct solve with the matrix factorised anew, whose factorisation then preconditions
    // the next solves.
    auto direct = [&] {
      refactor();
      stale = false;
      last_iterations = 0;
      ++report.linear_iterations;
      ++report.direct_solves;
      return preconditioner.solve(b, &lanes);
    };
    const bool first = solves_this_step++ == 0;
    // A later pass (another contact state from the same start) whose pass before needed more
    // than half of CG's iterations factorises at once: the passes after it then solve
    // directly, where each would take as many iterations again.
    const bool slow_pass = !first && 2 * last_iterations > options.max_linear_iterations;
    last_iterations = 0;
    if (!factorised || stale || slow_pass || (first && step_index < direct_until)) return direct();
    bool exact = factorised_terms == terms_found && same_other_contacts(factorised_contacts);
    // The cube's own terms (the floor's contacts with its corners come and go, stick and slide)
    // change the matrix on the cube's unknowns alone; ordered last, they are the factor's last
    // block, which takes the change exactly for the cost of a 6x6 factorisation.
    if (cube_trailing) {
      const Matrix6d change = cube_matrix() - cube_factorised;
      if (change != cube_applied && preconditioner.modify_trailing(cube_dofs, change))
        cube_applied = change;
      exact = exact && cube_applied == change;
    } else {
      exact = exact && cube_matrix() == cube_factorised;
    }
    if (exact) {
      ++report.linear_iterations;
      ++report.direct_solves;
      Eigen::VectorXd x = preconditioner.solve(b, &lanes);
      if (options.check_products) check_direct(x, b);
      return x;
    }
    // Converged when what is left of the residual would move no unknown, on its own, by more
    // than the tolerance: a criterion per unknown, because a relative norm is the flesh's and
    // lets a light cube's unknowns go unsolved.
    const Eigen::VectorXd inverse_diagonal = diagonal().cwiseInverse();
    auto left = [&](const Eigen::VectorXd& residual) {  // the largest move it would make
      return (residual.cwiseProduct(inverse_diagonal)).lpNorm<Eigen::Infinity>();
    };
    auto converged = [&](const Eigen::VectorXd& residual) {
      return left(residual) <= options.linear_tolerance;
    };
    Eigen::VectorXd x = Eigen::VectorXd::Zero(dofs), r = b, z = preconditioner.solve(r, &lanes),
                    p = z, ap;
    double rz = r.dot(z);
    int it = 0;
    bool done = converged(r);
    while (!done && it < options.max_linear_iterations) {
      multiply(p, ap);
      if (options.check_products) check_product(p, ap);
      const double pap = p.dot(ap);
      if (!(pap > 0)) break;
      const double alpha = rz / pap;
      x += alpha * p;
      r -= alpha * ap;
      ++it;
      // The next direction only for a next iteration: its solve is an iteration's larger cost.
      done = converged(r);
      if (done || it == options.max_linear_iterations) break;
      // Halfway and still far (the preconditioner is too far from the matrix): the iterations
      // left rarely close the gap, and the factorisation will be needed.
      if (options.halfway_gap > 0 && it == (options.max_linear_iterations + 1) / 2 &&
          left(r) > options.halfway_gap * options.linear_tolerance)
        break;
      z = preconditioner.solve(r, &lanes);
      const double rz_next = r.dot(z);
      p = z + (rz_next / rz) * p;
      rz = rz_next;
    }
    report.linear_iterations += it;
    stale = it > options.refactor_iterations;
    last_iterations = it;
    if (first) {
      // A preconditioner that has drifted from the matrix, if not enough to fail CG: renewed
      // after refresh_steps steps in a row that needed two iterations or more.
      slow_steps = it >= 2 ? slow_steps + 1 : 0;
      if (options.refresh_steps > 0 && slow_steps >= options.refresh_steps) {
        stale = true;
        slow_steps = 0;
      }
    }
    if (!done) {
      // CG did not converge with this preconditioner: factorise the matrix itself. If the
      // preconditioner was the previous step's matrix, the matrix is changing faster than CG
      // follows (tets crossing the stiffening threshold, contacts coming and going): the next
      // steps factorise at once rather than spend CG iterations first.
      if (first && factorised_at == step_index - 1)
        direct_until = step_index + 1 + options.direct_steps;
      return direct();
    }
    return x;
  }

  // Tests: the flesh's gradient (what flesh() just wrote, the rotations held) against central
  // differences of the line search's energy along a direction through every node.
  void check_flesh_gradient(const HandSimState& s) {
    const int count = int(flesh_tets.size());
    HandSimState moved = s;
    Eigen::VectorXd direction(3 * nodes);
    for (int i = 0; i < 3 * nodes; ++i) direction[i] = std::sin(1.0 + 7.3 * i);
    const double step = 1e-7;  // m: the energy's rounding against its curvature
    auto energy_at = [&](double t) {
      for (int n = 0; n < nodes; ++n)
        moved.node_position[std::size_t(n)] =
            s.node_position[std::size_t(n)] + t * direction.segment<3>(3 * n);
      return flesh_energy(moved, 0, std::size_t(count));
    };
    const double slope = (energy_at(step) - energy_at(-step)) / (2 * step);
    const double expected = gradient.head(3 * nodes).dot(direction);
    const double size = gradient.head(3 * nodes).cwiseAbs().dot(direction.cwiseAbs());
    if (!(std::abs(slope - expected) <= 1e-5 * size + 1e-12))
      throw std::logic_error(
          "HandSimulator: the flesh's forces differ from its energy's differences");
  }

  // Tests: a direct solve with a factor taken to be the matrix's leaves no more residual than
  // CG's tolerance.
  void check_direct(const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
    Eigen::VectorXd ax;
    multiply(x, ax);
    const double left = ((b - ax).cwiseQuotient(diagonal())).lpNorm<Eigen::Infinity>();
    if (!(left <= options.linear_tolerance))
      throw std::logic_error(
          "HandSimulator: a direct solve with the factor taken to be the matrix's leaves a "
          "residual beyond CG's tolerance");
  }

  // Tests: the term-by-term product and diagonal against the assembled matrix's.
  void check_product(const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
    assemble();
    const Eigen::VectorXd expected = matrix * x;
    // Rounding scales with the terms summed, |A| |x|, not with the (cancelling) result.
    const Eigen::VectorXd magnitude = matrix.cwiseAbs() * x.cwiseAbs();
    const double error = ((y - expected).cwiseAbs() - 1e-12 * magnitude).maxCoeff();
    const double diagonal_error = (diagonal() - matrix.diagonal()).lpNorm<Eigen::Infinity>() -
                                  1e-12 * matrix.diagonal().lpNorm<Eigen::Infinity>();
    if (!(error <= 0) || !(diagonal_error <= 0))
      throw std::logic_error(
          "HandSimulator: the Newton matrix's product or diagonal differs from "
          "the assembled one by more than rounding");
    // The assembly into the panels, entry by entry against the sparse matrix (rounding on the
    // scale of the entry's row and column: |A_rc| <= sqrt(A_rr A_cc), and an entry summed to
    // nearly zero keeps its terms' rounding).
    std::vector<double> panels(std::size_t(preconditioner.value_count()), 0.0);
    assemble_panels(panels.data());
    const Eigen::VectorXd diag = matrix.diagonal();
    double panel_error = 0.0;
    for (int col = 0; col < matrix.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(matrix, col); it; ++it) {
        const double stored = panels[std::size_t(preconditioner.position(int(it.row()), col))];
        panel_error = std::max(panel_error, std::abs(stored - it.value()) -
                                                1e-12 * std::sqrt(diag[it.row()] * diag[col]));
      }
    // Split between two lanes, the same sums bit for bit.
    std::vector<double> split(panels.size(), 0.0);
    assemble_panels(split.data(), 0);
    assemble_panels(split.data(), 1);
    if (!(panel_error <= 0) || split != panels)
      throw std::logic_error(
          "HandSimulator: the Newton matrix written into the panels differs from the assembled "
          "one");
  }

  // The state moved by `length` times the increment dq.
  void apply(HandSimState& s, std::vector<Eigen::Vector3d>& turned, const Eigen::VectorXd& dq,
             double length) const {
    for (int n = 0; n < nodes; ++n)
      s.node_position[std::size_t(n)] += length * dq.segment<3>(3 * n);
    auto move = [&](int block, RigidPose& pose, Eigen::Vector3d& rotated) {
      pose.position += length * dq.segment<3>(3 * block);
      const Eigen::Vector3d d_theta = length * dq.segment<3>(3 * (block + 1));
      rotated += d_theta;
      pose.rotation = (rotation_from_vector(d_theta) * pose.rotation).normalized();
    };
    for (int b = 0; b < bones; ++b)
      move(bone_block(b), s.bone_pose[std::size_t(b)], turned[std::size_t(b)]);
    move(cube_block(), s.cube_pose, turned.back());
  }
};

namespace {
const SimOptions& checked(const SimOptions& options) {
  if (options.newton_iterations < 1)
    throw std::invalid_argument("HandSimulator: at least one Newton iteration a step");
  if (options.threads < 1) throw std::invalid_argument("HandSimulator: at least one thread");
  return options;
}
}  // namespace

HandSimulator::HandSimulator(const HandSimModel& model, SimOptions options)
    : impl_(std::make_unique<Impl>(model, checked(options))) {}
HandSimulator::~HandSimulator() = default;
const HandSimModel& HandSimulator::model() const {
  return impl_->model;
}

SimStepReport HandSimulator::step(HandSimState& state, const std::vector<RigidPose>& targets) {
  Impl& im = *impl_;
  const HandSimModel& m = im.model;
  if (int(targets.size()) != m.bone_count())
    throw std::invalid_argument("HandSimulator::step: one target per bone");
  for (const RigidPose& t : targets)
    if (!t.position.allFinite() || !t.rotation.coeffs().allFinite() ||
        std::abs(t.rotation.norm() - 1.0) > 1e-6)
      throw std::invalid_argument("HandSimulator::step: a target that is not a finite pose");
  const double h = m.parameters.time_step;
  im.scale = h * h;
  // Predicted state: every body carried on by its velocity.
  const HandSimState start = state;
  ++im.step_index;
  im.solves_this_step = 0;
  std::vector<Eigen::Vector3d> turned(std::size_t(m.bone_count() + 1));  // rotation since start
  for (int n = 0; n < im.nodes; ++n)
    state.node_position[std::size_t(n)] += h * state.node_velocity[std::size_t(n)];
  auto predict = [&](RigidPose& pose, const RigidVelocity& v, Eigen::Vector3d& rotated) {
    pose.position += h * v.linear;
    rotated = h * v.angular;
    pose.rotation = (rotation_from_vector(rotated) * pose.rotation).normalized();
  };
  for (int b = 0; b < im.bones; ++b)
    predict(state.bone_pose[std::size_t(b)], state.bone_velocity[std::size_t(b)],
            turned[std::size_t(b)]);
  predict(state.cube_pose, state.cube_velocity, turned.back());
  im.find_contacts(state);

  // Newton on the step's energy, each step backtracked until the energy decreases (Armijo):
  // contacts make the energy piecewise quadratic, and a full step that runs into a surface the
  // linearisation did not see would land deep inside it.
  const StepFrame frame{&start, &targets};
  SimStepReport report;
  // Every pass starts from the prediction, the tets' rotations as the first pass found them
  // there, and (one Newton iteration a pass, so that its Hessian terms are still the first
  // evaluation's) takes the flesh's terms from the first pass: only contacts differ.
  HandSimState predicted;
  const std::vector<Eigen::Vector3d> predicted_turned = turned;
  for (int pass = 0; pass < kFrictionPasses; ++pass) {
    if (pass > 0) {
      state = predicted;
      turned = predicted_turned;
    }
    using Reuse = Impl::Reuse;
    const bool kept = pass > 0 && im.options.newton_iterations == 1;
    double current = im.evaluate(state, turned, frame, true, kept ? Reuse::kKept : Reuse::kKeep);
    if (pass == 0) predicted = state;
    for (int it = 0; it < im.options.newton_iterations; ++it) {
      report.residual = im.gradient.lpNorm<Eigen::Infinity>() / im.scale;
      const Eigen::VectorXd dq = im.solve(report);
      const double slope = im.gradient.dot(dq);
      HandSimState trial = state;
      std::vector<Eigen::Vector3d> trial_turned = turned;
      // No body turns by more than kMaxTurn in one iteration: the linearisation of a rotation
      // holds over a fraction of a radian, and a cube, symmetric under quarter turns, can
      // lower the energy by a turn of several radians that no physical step takes.
      double largest_turn = 0.0;
      for (int b = 0; b <= im.bones; ++b)
        largest_turn = std::max(largest_turn, dq.segment<3>(3 * (im.nodes + 2 * b + 1)).norm());
      double length = largest_turn > kMaxTurn ? kMaxTurn / largest_turn : 1.0;
      // Where the state already solves the step (CG's first residual within its tolerance, so
      // dq = 0), there is nothing to search: an energy evaluated again differs by rounding.
      for (int halving = 0; halving < 12 && slope < 0; ++halving, length *= 0.5) {
        trial = state;
        trial_turned = turned;
        im.apply(trial, trial_turned, dq, length);
        if (im.evaluate(trial, trial_turned, frame, false) <= current + 1e-4 * length * slope)
          break;
        ++report.halvings;
      }
      state = std::move(trial);
      turned = std::move(trial_turned);
      report.newton_iterations += 1;
      if (it + 1 < im.options.newton_iterations) current = im.evaluate(state, turned, frame, true);
    }
    const bool entered = im.contacts_entered(state);
    if (!im.friction_changed(state) && !entered) break;
  }
  // Velocities from the step taken.
  for (int n = 0; n < im.nodes; ++n)
    state.node_velocity[std::size_t(n)] =
        (state.node_position[std::size_t(n)] - start.node_position[std::size_t(n)]) / h;
  for (int b = 0; b < im.bones; ++b) {
    state.bone_velocity[std::size_t(b)].linear =
        (state.bone_pose[std::size_t(b)].position - start.bone_pose[std::size_t(b)].position) / h;
    state.bone_velocity[std::size_t(b)].angular = turned[std::size_t(b)] / h;
  }
  state.cube_velocity.linear = (state.cube_pose.position - start.cube_pose.position) / h;
  state.cube_velocity.angular = turned.back() / h;
  state.time = start.time + h;
  im.update_anchors(state, report.max_penetration);
  report.contacts =
      int(state.node_cube.size() + state.node_floor.size() + state.corner_floor.size());
  return report;
}

}  // namespace handlab::sim
