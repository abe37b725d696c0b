#include "core/sim/increment.h"

#include "core/sim/newton_terms.h"

namespace handlab::sim {

void apply_increment(const HandSimModel& model, HandSimState& state,
                     std::vector<Eigen::Vector3d>& turned, const Eigen::VectorXd& dq,
                     double length) {
  for (int n = 0; n < model.node_count(); ++n)
    state.node_position[std::size_t(n)] += length * dq.segment<3>(3 * n);
  auto turn = [&](int block, RigidPose& pose, Eigen::Vector3d& rotated) {
    pose.position += length * dq.segment<3>(3 * block);
    const Eigen::Vector3d d_theta = length * dq.segment<3>(3 * (block + 1));
    rotated += d_theta;
    pose.rotation = (rotation_from_vector(d_theta) * pose.rotation).normalized();
  };
  for (int b = 0; b < model.bone_count(); ++b)
    turn(bone_block(model, b), state.bone_pose[std::size_t(b)], turned[std::size_t(b)]);
  turn(cube_block(model), state.cube_pose, turned.back());
}

}  // namespace handlab::sim
