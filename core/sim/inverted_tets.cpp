#include "core/sim/inverted_tets.h"

#include "core/mesh/tet_mesh.h"

namespace handlab::sim {

// det F is the deformed volume over the rest volume, and every rest tet is positively oriented
// (make_tet_element): the sign of the deformed signed volume tells, at a tenth of F's cost.
int inverted_tet_count(const HandSimModel& model, const HandSimState& state) {
  int inverted = 0;
  for (const TetElement& tet : model.tets) {
    const auto x = [&](std::size_t a) -> const Eigen::Vector3d& {
      return state.node_position[std::size_t(tet.nodes[a])];
    };
    if (!(mesh::signed_volume(x(0), x(1), x(2), x(3)) > 0)) ++inverted;
  }
  return inverted;
}

}  // namespace handlab::sim
