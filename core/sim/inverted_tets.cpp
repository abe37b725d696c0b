#include "core/sim/inverted_tets.h"

#include <Eigen/LU>

namespace handlab::sim {

int inverted_tet_count(const HandSimModel& model, const HandSimState& state) {
  int inverted = 0;
  for (const TetElement& tet : model.tets) {
    std::array<Eigen::Vector3d, 4> x;
    for (std::size_t a = 0; a < 4; ++a) x[a] = state.node_position[std::size_t(tet.nodes[a])];
    if (!(deformation_gradient(tet, x).determinant() > 0)) ++inverted;
  }
  return inverted;
}

}  // namespace handlab::sim
