// A tet counts as inside out once a node has passed through its opposite face (det F <= 0),
// and not before, however hard it is squeezed.
#include <gtest/gtest.h>

#include "core/sim/inverted_tets.h"

namespace handlab::sim {
namespace {

TEST(InvertedTets, CountsTetsWhoseNodeCrossedTheOppositeFace) {
  // Two tets sharing the face 0-1-2, one above it (node 3) and one below (node 4).
  const mesh::TetMesh mesh{
      {Eigen::Vector3d::Zero(), Eigen::Vector3d(0.01, 0, 0), Eigen::Vector3d(0, 0.01, 0),
       Eigen::Vector3d(0, 0, 0.01), Eigen::Vector3d(0.002, 0.002, -0.01)},
      {{0, 1, 2, 3}, {0, 2, 1, 4}}};
  const HandSimModel model = make_soft_body_sim_model(mesh);
  HandSimState s;
  s.node_position = model.rest;
  EXPECT_EQ(inverted_tet_count(model, s), 0);
  s.node_position[3].z() = 1e-6;  // squeezed flat, still right side out
  EXPECT_EQ(inverted_tet_count(model, s), 0);
  s.node_position[3].z() = 0.0;  // flat: no volume left
  EXPECT_EQ(inverted_tet_count(model, s), 1);
  s.node_position[3].z() = -0.003;  // through the face
  EXPECT_EQ(inverted_tet_count(model, s), 1);
  s.node_position[4].z() = 0.002;  // the other tet's apex through it too
  EXPECT_EQ(inverted_tet_count(model, s), 2);
}

}  // namespace
}  // namespace handlab::sim
