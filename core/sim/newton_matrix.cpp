#include "core/sim/newton_matrix.h"

#include <algorithm>
#include <set>
#include <stdexcept>

#include "core/sim/thread_pool.h"

namespace handlab::sim {
namespace {

// y += (the tets' part of A) x, the batches [first, last).
void tet_products(const HandSimModel& model, const NewtonTerms& terms, const Eigen::VectorXd& x,
                  Eigen::VectorXd& y, std::size_t first, std::size_t last) {
  const std::size_t count = model.tets.size();
  for (std::size_t k = first; k < last; ++k) {
    const TetTerms4& t = terms.tets[k];
    const std::size_t e = kTetBatch * k;
    Lane4 p[12];  // x at the tets' nodes
    for (int l = 0; l < kTetBatch; ++l) {
      const auto& ids = model.tets[std::min(e + std::size_t(l), count - 1)].nodes;
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
    for (int l = 0; l < kTetBatch && e + std::size_t(l) < count; ++l) {
      const auto& ids = model.tets[e + std::size_t(l)].nodes;
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) y[3 * ids[std::size_t(a)] + i] += product[3 * a + i][l];
    }
  }
}

// The places a spring's `cached` takes for a spring on these blocks: 3x3 of them for each
// pair, at = -1 where the pair's mirror writes.
void spring_blocks(const SupernodalLdlt& factor, const std::vector<int>& point_blocks,
                   std::vector<PanelBlock>& out) {
  for (int a : point_blocks)
    for (int b : point_blocks)
      out.push_back(a == b || factor.ordered_after(3 * a, 3 * b) ? panel_block(factor, a, b)
                                                                 : PanelBlock{});
}

bool on_cube_alone(const HandSimModel& model, const SpringTerm& t) {
  for (int a = 0; a < t.p.count; ++a)
    if (t.p.block[std::size_t(a)] < cube_block(model)) return false;
  return true;
}

}  // namespace

Eigen::SparseMatrix<double> newton_pattern(const HandSimModel& m) {
  const int blocks = block_count(m), dofs = 3 * blocks, cube = cube_block(m);
  std::vector<std::set<int>> pairs(static_cast<std::size_t>(blocks));
  auto couple = [&](const std::vector<int>& group) {
    for (int a : group)
      for (int b : group) pairs[std::size_t(a)].insert(b);
  };
  for (int b = 0; b < blocks; ++b) pairs[std::size_t(b)].insert(b);
  for (const TetElement& t : m.tets) couple({t.nodes[0], t.nodes[1], t.nodes[2], t.nodes[3]});
  for (const SimCoupling& c : m.coupling)
    couple({c.nodes[0], c.nodes[1], c.nodes[2], c.nodes[3], bone_block(m, c.bone),
            bone_block(m, c.bone) + 1});
  for (const SimJoint& j : m.joints)
    couple({bone_block(m, j.parent), bone_block(m, j.parent) + 1, bone_block(m, j.child),
            bone_block(m, j.child) + 1});
  for (int n : m.surface_nodes) couple({n, cube, cube + 1});
  couple({cube, cube + 1});
  for (int b = 0; b < m.bone_count(); ++b) couple({bone_block(m, b), bone_block(m, b) + 1});
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < blocks; ++j)
    for (int i : pairs[std::size_t(j)])
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) entries.emplace_back(3 * i + r, 3 * j + c, 1.0);
  Eigen::SparseMatrix<double> pattern(dofs, dofs);
  pattern.setFromTriplets(entries.begin(), entries.end());
  pattern.makeCompressed();
  return pattern;
}

PanelBlock panel_block(const SupernodalLdlt& f, int bi, int bj) {
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

NewtonLayout make_newton_layout(const HandSimModel& m, const SupernodalLdlt& factor) {
  NewtonLayout layout;
  for (const TetElement& t : m.tets) {
    std::array<PanelBlock, 10> e;
    std::size_t k = 0;
    for (int a = 0; a < 4; ++a)
      for (int b = a; b < 4; ++b)
        e[k++] = panel_block(factor, t.nodes[std::size_t(a)], t.nodes[std::size_t(b)]);
    layout.tet_blocks.push_back(e);
  }
  for (const SimCoupling& c : m.coupling)
    spring_blocks(factor,
                  {c.nodes[0], c.nodes[1], c.nodes[2], c.nodes[3], bone_block(m, c.bone),
                   bone_block(m, c.bone) + 1},
                  layout.coupling_blocks);
  for (const SimJoint& j : m.joints)
    spring_blocks(factor,
                  {bone_block(m, j.parent), bone_block(m, j.parent) + 1, bone_block(m, j.child),
                   bone_block(m, j.child) + 1},
                  layout.joint_blocks);
  for (int b = 0; b < block_count(m); ++b)
    layout.diagonal_blocks.push_back(panel_block(factor, b, b));
  // Two workers write the panels below and from the panel that holds the median of the tets'
  // blocks (most of the assembly's work).
  std::vector<int> places;
  for (const auto& e : layout.tet_blocks)
    for (const PanelBlock& p : e) places.push_back(p.at);
  std::nth_element(places.begin(), places.begin() + std::ptrdiff_t(places.size() / 2),
                   places.end());
  layout.panel_split = places.empty() ? 0 : factor.panel_start(places[places.size() / 2]);
  const int tets = int(layout.tet_blocks.size());
  for (int k = 0; k * kTetBatch < tets; ++k)
    for (int share = 0; share < 2; ++share) {
      bool owned = false;
      for (int t = kTetBatch * k; t < std::min(tets, kTetBatch * (k + 1)); ++t)
        for (const PanelBlock& p : layout.tet_blocks[std::size_t(t)])
          owned = owned || (p.at >= 0 && (p.at >= layout.panel_split) == (share == 1));
      if (owned) layout.share_batches[std::size_t(share)].push_back(k);
    }
  return layout;
}

void multiply(const HandSimModel& model, const NewtonTerms& terms, const Eigen::VectorXd& x,
              Eigen::VectorXd& y, ThreadPool* pool, Eigen::VectorXd* scratch) {
  const int nodes = model.node_count(), dofs = model.dof_count();
  y.resize(dofs);
  y.tail(dofs - 3 * nodes).setZero();
  for (int n = 0; n < nodes; ++n)
    y.segment<3>(3 * n) = model.node_mass[std::size_t(n)] * x.segment<3>(3 * n);
  const std::size_t batches = terms.tets.size();
  if (pool && pool->workers() >= 2 && scratch) {
    // Two workers, each half of the batches, the second's into `scratch`, added afterwards.
    scratch->setZero(3 * nodes);
    pool->run([&](int worker) {
      if (worker == 0) tet_products(model, terms, x, y, 0, batches / 2);
      if (worker == 1) tet_products(model, terms, x, *scratch, batches / 2, batches);
    });
    y.head(3 * nodes) += *scratch;
  } else {
    tet_products(model, terms, x, y, 0, batches);
  }
  for (const SpringTerm& t : terms.springs) {
    Eigen::Vector3d u = Eigen::Vector3d::Zero();
    for (int a = 0; a < t.p.count; ++a)
      u += t.p.j[std::size_t(a)] * x.segment<3>(3 * t.p.block[std::size_t(a)]);
    const Eigen::Vector3d v = t.k * u;
    for (int a = 0; a < t.p.count; ++a)
      y.segment<3>(3 * t.p.block[std::size_t(a)]) += t.p.j[std::size_t(a)].transpose() * v;
  }
  for (const BlockTerm& t : terms.blocks)
    y.segment<3>(3 * t.block) += t.m * x.segment<3>(3 * t.block);
}

Eigen::VectorXd diagonal(const HandSimModel& model, const NewtonTerms& terms,
                         NewtonDiagonal& cache) {
  auto add_springs = [&](Eigen::VectorXd& diag, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const SpringTerm& t = terms.springs[i];
      for (int a = 0; a < t.p.count; ++a) {
        const Eigen::Matrix3d& j = t.p.j[std::size_t(a)];
        diag.segment<3>(3 * t.p.block[std::size_t(a)]) += (j.transpose() * t.k * j).diagonal();
      }
    }
  };
  auto add_blocks = [&](Eigen::VectorXd& diag, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      diag.segment<3>(3 * terms.blocks[i].block) += terms.blocks[i].m.diagonal();
  };
  if (!cache.known) {
    Eigen::VectorXd& diag = cache.base;
    diag.setZero(model.dof_count());
    for (int n = 0; n < model.node_count(); ++n)
      diag.segment<3>(3 * n).setConstant(model.node_mass[std::size_t(n)]);
    // A tet's diagonal block (a, a) has vmu (|r_a|^2 + r_a[i]^2) + vlambda r_a[i]^2 + q_a[i]^2
    // on its diagonal.
    const std::size_t count = model.tets.size();
    for (std::size_t k = 0; k < terms.tets.size(); ++k) {
      const TetTerms4& t = terms.tets[k];
      Lane4 d[12];
      for (int a = 0; a < 4; ++a) {
        const Lane4* r = t.rotated + 3 * a;
        const Lane4 length = t.vmu * (r[0].square() + r[1].square() + r[2].square());
        for (int i = 0; i < 3; ++i)
          d[3 * a + i] = length + (t.vmu + t.vlambda) * r[i].square() + t.q[3 * a + i].square();
      }
      for (int l = 0; l < kTetBatch && kTetBatch * k + std::size_t(l) < count; ++l) {
        const auto& ids = model.tets[kTetBatch * k + std::size_t(l)].nodes;
        for (int a = 0; a < 4; ++a)
          for (int i = 0; i < 3; ++i) diag[3 * ids[std::size_t(a)] + i] += d[3 * a + i][l];
      }
    }
    add_springs(diag, 0, terms.first_contact_spring);
    add_blocks(diag, 0, terms.first_contact_block);
    cache.known = true;
  }
  Eigen::VectorXd diag = cache.base;
  add_springs(diag, terms.first_contact_spring, terms.springs.size());
  add_blocks(diag, terms.first_contact_block, terms.blocks.size());
  return diag;
}

namespace {

// The cube-cube block of the matrix from the terms `counted` takes (springs from `first`; the
// blocks on the cube's unknowns).
template <typename Counted>
Matrix6d cube_part(const HandSimModel& model, const NewtonTerms& terms, std::size_t first,
                   Counted counted) {
  Matrix6d m = Matrix6d::Zero();
  const int cube = cube_block(model);
  for (std::size_t i = first; i < terms.springs.size(); ++i) {
    const SpringTerm& t = terms.springs[i];
    if (!counted(t)) continue;
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
  for (const BlockTerm& t : terms.blocks)
    if (t.block >= cube) m.block<3, 3>(3 * (t.block - cube), 3 * (t.block - cube)) += t.m;
  return m;
}

}  // namespace

// Of the springs only the contacts' can be on the cube alone.
Matrix6d cube_matrix(const HandSimModel& model, const NewtonTerms& terms) {
  return cube_part(model, terms, terms.first_contact_spring,
                   [&](const SpringTerm& t) { return on_cube_alone(model, t); });
}

Matrix6d cube_block_matrix(const HandSimModel& model, const NewtonTerms& terms) {
  return cube_part(model, terms, 0, [](const SpringTerm&) { return true; });
}

void other_contacts(const HandSimModel& model, const NewtonTerms& terms,
                    std::vector<SpringTerm>& out) {
  out.clear();
  for (std::size_t i = terms.first_contact_spring; i < terms.springs.size(); ++i)
    if (!on_cube_alone(model, terms.springs[i])) out.push_back(terms.springs[i]);
}

bool same_other_contacts(const HandSimModel& model, const NewtonTerms& terms,
                         const std::vector<SpringTerm>& known) {
  std::size_t k = 0;
  for (std::size_t i = terms.first_contact_spring; i < terms.springs.size(); ++i) {
    const SpringTerm& t = terms.springs[i];
    if (on_cube_alone(model, t)) continue;
    if (k == known.size()) return false;
    const SpringTerm& u = known[k++];
    if (t.p.count != u.p.count || t.p.block != u.p.block || t.k != u.k) return false;
    for (int a = 0; a < t.p.count; ++a)
      if (t.p.j[std::size_t(a)] != u.p.j[std::size_t(a)]) return false;
  }
  return k == known.size();
}

void write_panels(const HandSimModel& model, const NewtonTerms& terms, const NewtonLayout& layout,
                  const SupernodalLdlt& factor, double* values, int share) {
  auto owns = [&](int at) { return share < 0 || (at >= layout.panel_split) == (share == 1); };
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
  for (int n = 0; n < model.node_count(); ++n) {
    const PanelBlock& p = layout.diagonal_blocks[std::size_t(n)];
    if (!owns(p.at)) continue;
    for (int c = 0; c < 3; ++c)
      values[p.at + (p.stride + 1) * c] += model.node_mass[std::size_t(n)];
  }
  const std::size_t count = model.tets.size();
  // A worker computes the blocks of the batches that have a place in its panels only.
  const std::size_t batches =
      share < 0 ? terms.tets.size() : layout.share_batches[std::size_t(share)].size();
  for (std::size_t i = 0; i < batches; ++i) {
    const std::size_t k = share < 0 ? i : std::size_t(layout.share_batches[std::size_t(share)][i]);
    const TetTerms4& t = terms.tets[k];
    // Block (a, b) of the four tets, entry (r, c) at 9 n + r + 3 c for the n-th pair a <= b:
    // vmu r_b[r] r_a[c] + vlambda r_a[r] r_b[c] + q_a[r] q_b[c], and vmu r_a . r_b on its
    // diagonal.
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
    for (int l = 0; l < kTetBatch && kTetBatch * k + std::size_t(l) < count; ++l) {
      const auto& places = layout.tet_blocks[kTetBatch * k + std::size_t(l)];
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
  for (const SpringTerm& t : terms.springs) {
    const PointJacobian& p = t.p;
    for (int a = 0; a < p.count; ++a) {
      const Eigen::Matrix3d jk = p.j[std::size_t(a)].transpose() * t.k;
      for (int b = 0; b < p.count; ++b) {
        const int ba = p.block[std::size_t(a)], bb = p.block[std::size_t(b)];
        PanelBlock place;
        if (t.cached)
          place = t.cached[p.count * a + b];
        else if (ba == bb || factor.ordered_after(3 * ba, 3 * bb))
          place = panel_block(factor, ba, bb);
        if (place.at < 0 || !owns(place.at)) continue;  // its mirror (b, a) writes it
        const Eigen::Matrix3d block = jk * p.j[std::size_t(b)];
        if (ba == bb)
          add_diagonal(place, block);
        else
          add(place, block);
      }
    }
  }
  for (const BlockTerm& t : terms.blocks)
    if (owns(layout.diagonal_blocks[std::size_t(t.block)].at))
      add_diagonal(layout.diagonal_blocks[std::size_t(t.block)], t.m);
}

}  // namespace handlab::sim
