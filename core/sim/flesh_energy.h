// The flesh: linear co-rotational FEM with a stiffening term, per tet. F from the edge
// vectors, R its polar rotation (extracted where Newton linearises, held through its line
// search: there the energy is the quadratic its Hessian describes), the strain
// e = sym(R'F) - I, the stress s = 2 mu e + lambda tr(e) I, node forces V R s grad N_a, and the
// Hessian R K R' as the tets' terms (newton_terms.h). Beyond a strain norm e0 the tissue
// stiffens: (k V / 2)(|e| - e0)^2 on top. Four tets at a time, one in each SIMD lane.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "core/sim/hand_sim_model.h"
#include "core/sim/hand_sim_state.h"
#include "core/sim/newton_terms.h"
#include "core/sim/thread_pool.h"

namespace handlab::sim {

// Each worker's forces and energy (worker 0's forces go into the gradient itself), summed in
// worker order so that the result depends on the worker count alone.
struct FleshBuffers {
  std::vector<Eigen::VectorXd> forces;
  std::vector<double> energy;
};

// Adds the flesh to `terms`: with its Hessian, the tets' rotations are extracted anew (into
// state.tet_rotation, from the last as a warm start), and the forces and tets' terms found;
// without (the line search), the energy alone at the held rotations.
void add_flesh(const HandSimModel& model, HandSimState& state, NewtonTerms& terms, ThreadPool& pool,
               FleshBuffers& buffers);

// h^2 (`scale`) times the energy of tets [begin, end) at the rotations in the state.
double flesh_energy(const HandSimModel& model, const HandSimState& state, std::size_t begin,
                    std::size_t end, double scale);

}  // namespace handlab::sim
