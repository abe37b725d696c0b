// Physics tests of the simulator's flesh against known answers.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "core/mesh/tetrahedralize.h"
#include "core/sim/rotation_extraction.h"
#include "tests/core/sim/reference/elastic_body.h"

namespace handlab::sim {
namespace {

const Material kFlesh{50e3, 0.45};

// A closed box surface [0,a]x[0,b]x[0,c], triangles counter-clockwise from outside.
mesh::SurfaceMesh box_surface(double a, double b, double c) {
  mesh::SurfaceMesh s;
  for (int k = 0; k < 8; ++k) s.vertices.emplace_back(k & 1 ? a : 0, k & 2 ? b : 0, k & 4 ? c : 0);
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    s.triangles.push_back({q[0], q[1], q[2]});
    s.triangles.push_back({q[0], q[2], q[3]});
  }
  return s;
}

// The TetGen mesh of a 4 x 3 x 2 cm box, with interior nodes.
mesh::TetMesh box_mesh() {
  mesh::TetrahedralizeOptions options;
  options.max_volume = 2e-8;
  options.keep_boundary = false;  // with -Y TetGen adds no point to a box at all
  return mesh::tetrahedralize(box_surface(0.04, 0.03, 0.02), options);
}

bool on_box_boundary(const Eigen::Vector3d& p) {
  const double e = 1e-12;
  return p.x() < e || p.y() < e || p.z() < e || p.x() > 0.04 - e || p.y() > 0.03 - e ||
         p.z() > 0.02 - e;
}

ElasticBodyModel weightless(const mesh::TetMesh& mesh, const Material& material) {
  ElasticBodyModel model = make_elastic_body(mesh, material, 1000.0);
  model.gravity.setZero();
  return model;
}

Eigen::Matrix3d random_rotation(std::mt19937& rng, double max_angle) {
  std::uniform_real_distribution<double> unit(-1, 1);
  const Eigen::Vector3d axis = Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized();
  return Eigen::AngleAxisd(max_angle * unit(rng), axis).toRotationMatrix();
}

TEST(RotationExtraction, RecoversThePolarRotation) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix3d r = random_rotation(rng, 3.0);
    Eigen::Matrix3d s = Eigen::Matrix3d::Identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j <= i; ++j) s(i, j) = s(j, i) = (i == j ? 1.0 : 0.0) + 0.2 * unit(rng);
    Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
    extract_rotation(r * s, q, 100);
    EXPECT_LT((q.toRotationMatrix() - r).norm(), 1e-9) << trial;
  }
}

// Four at once (the flesh's batches): warm-started near their rotations the lanes settle in
// their two turns; a lane started far, or an F near inversion, goes to extract_rotation. Every
// lane ends at the polar rotation, whatever the others do, and lanes past `count` are left.
TEST(RotationExtraction, FourAtOnceAsOneByOne) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 40; ++trial) {
    Eigen::Array4d f[9];
    std::array<Eigen::Matrix3d, 4> r, a;
    std::array<Eigen::Quaterniond, 4> q;
    const int count = trial % 4 + 1;
    int warm_lanes = 0;  // of the first `count`, started near and not flat
    for (int l = 0; l < 4; ++l) {
      r[std::size_t(l)] = random_rotation(rng, 3.0);
      Eigen::Matrix3d s = Eigen::Matrix3d::Identity();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j <= i; ++j) s(i, j) = s(j, i) = (i == j ? 1.0 : 0.0) + 0.2 * unit(rng);
      const bool flat = trial % 5 == 4 && l == 2;
      if (flat) s.col(0) *= 1e-4;
      a[std::size_t(l)] = r[std::size_t(l)] * s;
      for (int i = 0; i < 9; ++i) f[i][l] = a[std::size_t(l)](i / 3, i % 3);
      // Warm: the rotation turned by up to 0.02 rad (as from one step to the next); or cold.
      const bool warm = (trial + l) % 3 != 0;
      warm_lanes += warm && !flat && l < count;
      q[std::size_t(l)] = warm ? Eigen::Quaterniond(random_rotation(rng, 0.02) * r[std::size_t(l)])
                               : Eigen::Quaterniond::Identity();
    }
    const std::array<Eigen::Quaterniond, 4> before = q;
    Eigen::Quaterniond* const lanes[4] = {&q[0], &q[1], &q[2], &q[3]};
    const int settled = extract_rotations(f, lanes, count);
    EXPECT_GE(settled, warm_lanes) << trial << ": the warm lanes settle in their two turns";
    EXPECT_LE(settled, count);
    for (int l = 0; l < 4; ++l) {
      if (l >= count) {
        EXPECT_EQ(q[std::size_t(l)].coeffs(), before[std::size_t(l)].coeffs()) << "lane " << l;
        continue;
      }
      Eigen::Quaterniond one = before[std::size_t(l)];
      extract_rotation(a[std::size_t(l)], one);
      EXPECT_LT((q[std::size_t(l)].toRotationMatrix() - one.toRotationMatrix()).norm(), 1e-9)
          << trial << " lane " << l;
      const Eigen::Matrix3d g =
          q[std::size_t(l)].toRotationMatrix().transpose() * a[std::size_t(l)];
      EXPECT_LT((g - g.transpose()).norm(), 1e-9 * g.norm()) << "R'F symmetric: " << trial;
    }
  }
}

// A linear displacement field gives every tet the same strain and no interior node a force.
TEST(CorotatedFem, PatchTest) {
  const mesh::TetMesh mesh = box_mesh();
  const ElasticBodyModel model = weightless(mesh, kFlesh);
  ElasticBodySolver solver(model);
  Eigen::Matrix3d a;
  a << 1.02, 0.01, -0.005, 0.003, 0.985, 0.008, -0.004, 0.006, 1.01;
  a = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix() * a;
  ElasticBodyState state = rest_state(model);
  int interior = 0;
  for (std::size_t i = 0; i < state.position.size(); ++i) {
    state.position[i] = a * model.rest[i] + Eigen::Vector3d(0.1, -0.2, 0.3);
    interior += !on_box_boundary(model.rest[i]);
  }
  ASSERT_GT(interior, 10) << "the mesh needs interior nodes: " << mesh.nodes.size() << " nodes, "
                          << mesh.tets.size() << " tets";
  Eigen::VectorXd g;
  solver.potential(state, {}, &g);
  // The strain of the polar decomposition of A, in every tet.
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  extract_rotation(a, q, 100);
  const Eigen::Matrix3d expected =
      0.5 * (q.toRotationMatrix().transpose() * a + a.transpose() * q.toRotationMatrix()) -
      Eigen::Matrix3d::Identity();
  for (std::size_t e = 0; e < model.tets.size(); ++e) {
    const auto& t = model.tets[e];
    const std::array<Eigen::Vector3d, 4> x = {
        state.position[std::size_t(t.nodes[0])], state.position[std::size_t(t.nodes[1])],
        state.position[std::size_t(t.nodes[2])], state.position[std::size_t(t.nodes[3])]};
    ASSERT_LT((corotated_strain(t, x, state.rotation[e].toRotationMatrix()) - expected).norm(),
              1e-10)
        << "tet " << e;
  }
  double largest = 0.0, interior_worst = 0.0;
  for (std::size_t i = 0; i < state.position.size(); ++i) {
    const double f = g.segment<3>(Eigen::Index(3 * i)).norm();
    largest = std::max(largest, f);
    if (!on_box_boundary(model.rest[i])) interior_worst = std::max(interior_worst, f);
  }
  EXPECT_GT(largest, 1e-3) << "the boundary carries the stress";
  EXPECT_LT(interior_worst, 1e-10);
}

TEST(CorotatedFem, RigidMotionsHaveNoElasticForce) {
  const mesh::TetMesh mesh = box_mesh();
  const ElasticBodyModel model = weightless(mesh, kFlesh);
  ElasticBodySolver solver(model);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Matrix3d r = random_rotation(rng, 3.1);
    const Eigen::Vector3d t(unit(rng), unit(rng), unit(rng));
    ElasticBodyState state = rest_state(model);
    for (std::size_t i = 0; i < state.position.size(); ++i)
      state.position[i] = r * model.rest[i] + t;
    Eigen::VectorXd g;
    const double u = solver.potential(state, {}, &g);
    EXPECT_LT(std::abs(u), 1e-12) << trial;  // J; a 1 mm stretch stores about 1e-4
    EXPECT_LT(g.lpNorm<Eigen::Infinity>(), 1e-10) << trial;
  }
}

// The co-rotated force is the exact gradient of the energy (the polar decomposition's R).
TEST(CorotatedFem, GradientMatchesFiniteDifferences) {
  const mesh::TetMesh mesh = box_mesh();
  const ElasticBodyModel model = weightless(mesh, kFlesh);
  ElasticBodySolver solver(model);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.002);
  ElasticBodyState state = rest_state(model);
  for (auto& p : state.position) p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  Eigen::VectorXd g;
  solver.potential(state, {}, &g);
  const double h = 1e-7;
  for (int d : {0, 7, 35, 101, 3 * int(state.position.size()) - 1}) {
    ElasticBodyState plus = state, minus = state;
    plus.position[std::size_t(d / 3)](d % 3) += h;
    minus.position[std::size_t(d / 3)](d % 3) -= h;
    const double fd =
        (solver.potential(plus, {}, nullptr) - solver.potential(minus, {}, nullptr)) / (2 * h);
    EXPECT_NEAR(g(d), fd, 1e-6 * std::max(1.0, std::abs(fd))) << "dof " << d;
  }
}

// Backward Euler on an undamped spring: the energy (in the norm where the map is
// I + h omega J, J skew) shrinks by exactly 1 / (1 + omega^2 h^2) a step, from any state.
TEST(BackwardEuler, SpringEnergyRatio) {
  ElasticBodyModel model;
  model.rest = {Eigen::Vector3d::Zero()};
  model.mass = {0.05};
  model.fixed = {false};
  model.springs = {{0, 200.0}};
  model.gravity.setZero();
  model.time_step = 1.0 / 120.0;
  ElasticBodySolver solver(model);
  const double omega2 = 200.0 / 0.05, h = model.time_step;
  ElasticBodyState state = rest_state(model);
  state.position[0] = Eigen::Vector3d(0.01, -0.004, 0.002);
  state.velocity[0] = Eigen::Vector3d(-0.3, 0.1, 0.2);
  auto energy = [&] {
    return 0.5 * 0.05 * state.velocity[0].squaredNorm() +
           0.5 * 200.0 * state.position[0].squaredNorm();
  };
  for (int step = 0; step < 5; ++step) {
    const double before = energy();
    solver.step(state, {Eigen::Vector3d::Zero()});
    EXPECT_NEAR(energy() / before, 1.0 / (1.0 + omega2 * h * h), 1e-12) << step;
  }
}

// A regular bar of n_w x n_w x 10 n_w cubes, each split into six tets (Kuhn).
mesh::TetMesh bar_mesh(double length, double width, int n_w) {
  const int n_l = 10 * n_w;
  mesh::TetMesh m;
  auto id = [&](int i, int j, int k) { return (i * (n_w + 1) + j) * (n_w + 1) + k; };
  for (int i = 0; i <= n_l; ++i)
    for (int j = 0; j <= n_w; ++j)
      for (int k = 0; k <= n_w; ++k)
        m.nodes.emplace_back(length * i / n_l, width * j / n_w, width * k / n_w);
  const int paths[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
  for (int i = 0; i < n_l; ++i)
    for (int j = 0; j < n_w; ++j)
      for (int k = 0; k < n_w; ++k)
        for (const auto& path : paths) {
          std::array<int, 4> t;
          int corner = 0;
          t[0] = id(i, j, k);
          for (int s = 0; s < 3; ++s) {
            corner |= path[s];
            t[std::size_t(s + 1)] =
                id(i + (corner & 1), j + ((corner >> 1) & 1), k + (corner >> 2));
          }
          if (mesh::signed_volume(m.nodes[std::size_t(t[0])], m.nodes[std::size_t(t[1])],
                                  m.nodes[std::size_t(t[2])], m.nodes[std::size_t(t[3])]) < 0)
            std::swap(t[2], t[3]);
          m.tets.push_back(t);
        }
  return m;
}

// A clamped bar under a tip load: the deflection converges towards PL^3 / 3EI as the mesh is
// refined (linear tets lock in bending, so it approaches from below).
TEST(CorotatedFem, CantileverConvergesToEulerBernoulli) {
  const double length = 0.1, width = 0.01, load = 1e-3;
  const Material material{1e6, 0.25};
  const double inertia = std::pow(width, 4) / 12.0;
  const double expected = load * std::pow(length, 3) / (3.0 * material.youngs_modulus * inertia);
  std::vector<double> errors;
  for (int n_w : {1, 2, 3, 4, 6}) {
    const mesh::TetMesh mesh = bar_mesh(length, width, n_w);
    ElasticBodyModel model = weightless(mesh, material);
    std::vector<Eigen::Vector3d> forces(mesh.nodes.size(), Eigen::Vector3d::Zero());
    int tip_nodes = 0;
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
      model.fixed[i] = mesh.nodes[i].x() < 1e-12;
      tip_nodes += mesh.nodes[i].x() > length - 1e-12;
    }
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
      if (mesh.nodes[i].x() > length - 1e-12) forces[i] = Eigen::Vector3d(0, -load / tip_nodes, 0);
    ElasticBodySolver solver(model);
    ElasticBodyState state = rest_state(model);
    const StepReport r = solver.solve_static(state, {}, forces, 30, 1e-12);
    EXPECT_LT(r.residual, 1e-12);
    double tip = 0.0;
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i)
      if (mesh.nodes[i].x() > length - 1e-12) tip += (model.rest[i] - state.position[i]).y();
    tip /= tip_nodes;
    errors.push_back(std::abs(tip - expected) / expected);
    std::printf(
        "cantilever %d x %d x %d cubes, %zu tets: tip %.4f mm, Euler-Bernoulli %.4f mm, "
        "error %.1f %%\n",
        n_w, n_w, 10 * n_w, mesh.tets.size(), 1e3 * tip, 1e3 * expected, 100 * errors.back());
  }
  for (std::size_t k = 1; k < errors.size(); ++k) EXPECT_LT(errors[k], errors[k - 1]);
  EXPECT_LT(errors.back(), 0.10);
}

}  // namespace
}  // namespace handlab::sim
