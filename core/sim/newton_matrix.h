// The Newton matrix held as its terms (newton_terms.h): where its blocks lie in the
// factorisation's panels, its product and diagonal for conjugate gradients, the part on the
// cube alone that the factor's last block follows, and writing it into the panels for a
// factorisation.
#pragma once

#include <array>
#include <vector>

#include <Eigen/SparseCore>

#include "core/sim/hand_sim_model.h"
#include "core/sim/newton_terms.h"
#include "core/sim/supernodal_ldlt.h"

namespace handlab::sim {

class ThreadPool;

// Every pair of blocks some energy couples (3x3 entries each, values 1), the pattern the
// factorisation is analysed on.
Eigen::SparseMatrix<double> newton_pattern(const HandSimModel& model);

// Where the terms go in the panels of a factorisation analysed on newton_pattern: fixed by the
// model and the factorisation's ordering.
struct NewtonLayout {
  std::vector<std::array<PanelBlock, 10>> tet_blocks;  // each tet's node pairs a <= b
  // A spring's 3x3 places per block pair (at = -1 where the pair's mirror writes): 36 a
  // coupling (its six blocks), 16 a joint (four).
  std::vector<PanelBlock> coupling_blocks, joint_blocks;
  std::vector<PanelBlock> diagonal_blocks;  // each block's (b, b)
  int panel_split = 0;  // the first value of the second worker's panels (write_panels)
  // The tet batches with a block in each worker's panels (a batch with blocks in both is in
  // both: the mesh's tets lie in no order of the panels).
  std::array<std::vector<int>, 2> share_batches;
};
NewtonLayout make_newton_layout(const HandSimModel& model, const SupernodalLdlt& factor);

// Block (bi, bj)'s place; std::logic_error unless it is a 3x3 block of a panel.
PanelBlock panel_block(const SupernodalLdlt& factor, int bi, int bj);

// y = A x, term by term (the node masses, the kinetic Hessian of the flesh, are the model's).
// With a pool of two workers and a `scratch` vector, the tets' products are split between
// them (the sums then in another order: the last digits differ from one worker's).
void multiply(const HandSimModel& model, const NewtonTerms& terms, const Eigen::VectorXd& x,
              Eigen::VectorXd& y, ThreadPool* pool = nullptr, Eigen::VectorXd* scratch = nullptr);

// The matrix's diagonal, term by term. The part of the terms before the contacts' is found once
// per evaluation that found them anew (clear `known` then) and kept here.
struct NewtonDiagonal {
  Eigen::VectorXd base;
  bool known = false;
};
Eigen::VectorXd diagonal(const HandSimModel& model, const NewtonTerms& terms,
                         NewtonDiagonal& cache);

// The part of the matrix's cube-cube block from terms on the cube alone (its inertia, the
// floor's contacts with its corners).
Matrix6d cube_matrix(const HandSimModel& model, const NewtonTerms& terms);
// The whole cube-cube block, from every term on the cube's unknowns (with the flesh's contacts).
Matrix6d cube_block_matrix(const HandSimModel& model, const NewtonTerms& terms);
// The contact terms that reach other unknowns than the cube's, and whether they equal `known`
// bit for bit (the same contacts evaluated at the same state).
void other_contacts(const HandSimModel& model, const NewtonTerms& terms,
                    std::vector<SpringTerm>& out);
bool same_other_contacts(const HandSimModel& model, const NewtonTerms& terms,
                         const std::vector<SpringTerm>& known);

// The matrix added straight into the factorisation's panel values (the lower triangle after
// its ordering; SupernodalLdlt::position): `values` the factorisation's own (cleared) or a copy.
// With `share` 0 or 1, only the blocks below or from layout.panel_split: two workers write
// disjoint values, each in the order the whole assembly adds them, so that the sums are the
// same bit for bit.
void write_panels(const HandSimModel& model, const NewtonTerms& terms, const NewtonLayout& layout,
                  const SupernodalLdlt& factor, double* values, int share = -1);

}  // namespace handlab::sim
