#include <gtest/gtest.h>

#include <array>
#include <atomic>
#include <numbers>
#include <thread>

#include "core/hand/hand_shape.h"
#include "core/hand/simulated_hand.h"
#include "core/hand/skin.h"
#include "core/mesh/surface_mesh.h"
#include "core/mesh/tet_mesh.h"
#include "core/mesh/tetrahedralize.h"

namespace handlab::mesh {
namespace {

TEST(Icosphere, IsAClosedOrientedSphere) {
  const SurfaceMesh sphere = make_icosphere(0.02, 2);
  EXPECT_EQ(sphere.triangles.size(), 320u);
  const SurfaceTopology t = surface_topology(sphere);
  EXPECT_TRUE(t.every_edge_shared_by_two);
  EXPECT_TRUE(t.consistently_oriented);
  EXPECT_EQ(t.euler_characteristic, 2);
  EXPECT_GT(enclosed_volume(sphere), 0.0);
}

TEST(Tetrahedralize, ClosedSurfaceGivesPositiveTetsFillingIt) {
  const SurfaceMesh sphere = make_icosphere(0.02, 2);
  const TetMesh mesh = tetrahedralize(sphere);
  const TetQuality q = tet_quality(mesh);
  EXPECT_GT(q.tets, 100);
  EXPECT_GT(q.min_volume, 0.0) << "every tet must have positive volume";
  // The tets fill exactly the polyhedron the surface encloses (-Y keeps the boundary).
  EXPECT_NEAR(q.total_volume, enclosed_volume(sphere), 1e-9 * enclosed_volume(sphere) + 1e-15);
  EXPECT_LE(q.max_radius_edge_ratio, 2.0);
  EXPECT_GT(q.min_dihedral_deg, 5.0);
  // The boundary was kept: every surface vertex is a node.
  EXPECT_GE(mesh.nodes.size(), sphere.vertices.size());
}

TEST(Tetrahedralize, VolumeBoundRefines) {
  const SurfaceMesh sphere = make_icosphere(0.02, 1);
  TetrahedralizeOptions coarse, fine;
  fine.max_volume = 1e-8;
  EXPECT_GT(tetrahedralize(sphere, fine).tets.size(),
            2 * tetrahedralize(sphere, coarse).tets.size());
}

TEST(Tetrahedralize, OpenSurfaceIsAnErrorNotAnEmptyMesh) {
  SurfaceMesh open = make_icosphere(0.02, 1);
  open.triangles.pop_back();
  EXPECT_THROW(tetrahedralize(open), std::runtime_error);
}

// TetGen's exact predicates keep their error bounds and splitter in globals that every run
// re-initialises (exactinit). Run bare, a run on another thread changes or crashes this one
// (without the lock 1 to 4 of these 12 meshes differ, in 6 runs of 6; a scratch check: 1 of
// 3,000 pairs started together), and a study's two jobs each mesh a soft hand at its start.
TEST(Tetrahedralize, RunsOnTwoThreadsGiveTheMeshOfARunAlone) {
  const hand::HandShape shape;
  const SurfaceMesh skin = hand::build_skin(hand::build_simulated_hand(shape), shape).surface;
  const TetMesh alone = tetrahedralize(skin);

  SurfaceMesh small;  // a box, meshed in a fraction of a millisecond
  for (int i = 0; i < 8; ++i)
    small.vertices.push_back(0.05 * Eigen::Vector3d(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  for (const auto& q : {std::array{0, 2, 3, 1}, std::array{4, 5, 7, 6}, std::array{0, 1, 5, 4},
                        std::array{2, 6, 7, 3}, std::array{0, 4, 6, 2}, std::array{1, 3, 7, 5}}) {
    small.triangles.push_back({q[0], q[1], q[2]});
    small.triangles.push_back({q[0], q[2], q[3]});
  }
  std::atomic<bool> stop{false};
  std::atomic<int> others{0};
  std::thread other([&] {
    while (!stop) {
      (void)tetrahedralize(small);
      ++others;
    }
  });
  int differ = 0;
  for (int i = 0; i < 12; ++i) {
    const TetMesh again = tetrahedralize(skin);
    differ += again.tets != alone.tets || again.nodes != alone.nodes;
  }
  stop = true;
  other.join();
  EXPECT_GT(others.load(), 0);
  EXPECT_EQ(differ, 0) << "of 12 hand meshes built while another thread meshed";
}

TEST(TetQuality, RegularTetrahedron) {
  TetMesh m;
  m.nodes = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  m.tets = {{0, 1, 2, 3}};
  if (signed_volume(m.nodes[0], m.nodes[1], m.nodes[2], m.nodes[3]) < 0)
    std::swap(m.tets[0][2], m.tets[0][3]);
  const TetQuality q = tet_quality(m);
  EXPECT_NEAR(q.max_radius_edge_ratio, std::sqrt(6.0) / 4.0, 1e-12);
  EXPECT_NEAR(q.min_dihedral_deg, std::acos(1.0 / 3.0) * 180.0 / std::numbers::pi, 1e-9);
  EXPECT_NEAR(q.total_volume, 8.0 / 3.0, 1e-12);
}

}  // namespace
}  // namespace handlab::mesh
