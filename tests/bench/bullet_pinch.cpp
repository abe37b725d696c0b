// A peer measured beside handlab's simulator: Bullet 3.24's implicit deformable solver
// (btDeformableMultiBodyDynamicsWorld) running the scripted pinch-and-lift of sim bench and
// sim pinch on the same hand: the same TetGen flesh, node masses, co-rotational linear
// elasticity at the same Young's modulus and Poisson ratio, the same time step, the cube a
// rigid body of the same size and mass, the floor under it (hand-floor contact off, as in the
// study). What differs, because Bullet has no such parts: the bones are kinematic bodies
// placed on their targets each step (handlab pulls dynamic bones towards them by springs), and
// the flesh around the bones (the nodes of the coupling points' tets) is held to them by
// Bullet's deformable anchors (handlab ties the coupling points by springs);
// Bullet has no stiffening term. Each run reports the time a step takes (median, p95),
// whether the cube is held through the hold and let go, how far it slips between the pads and
// how deep the flesh goes into it, by the rules of run_pinch; handlab's run of the same script
// in the same process beside it.
//
//   handlab_bullet_pinch [--cube 0.01|0.06] [--duration S] [--substeps N] [--json OUT]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDeformableBodySolver.h>
#include <BulletSoftBody/btDeformableMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDeformableMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <btBulletDynamicsCommon.h>

#include "core/sim/box_distance.h"
#include "core/sim/hand_simulator.h"
#include "core/task/pinch_scene.h"
#include "core/task/pinch_script.h"

namespace {

using handlab::sim::HandSimModel;
using handlab::sim::HandSimState;
using handlab::sim::PinchScene;
using handlab::sim::RigidPose;

// Collision groups: the floor meets the cube only, the flesh the cube only, the bones nothing.
constexpr int kFloor = 1, kCube = 2, kFlesh = 4, kBones = 8;

btVector3 bt(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}
Eigen::Vector3d eigen(const btVector3& v) {
  return {v.x(), v.y(), v.z()};
}
btTransform bt(const RigidPose& p) {
  return btTransform(btQuaternion(p.rotation.x(), p.rotation.y(), p.rotation.z(), p.rotation.w()),
                     bt(p.position));
}
RigidPose pose(const btTransform& t) {
  RigidPose p;
  const btQuaternion q = t.getRotation();
  p.position = eigen(t.getOrigin());
  p.rotation = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z());
  return p;
}

struct Percentiles {
  double median = 0.0, p95 = 0.0, max = 0.0;
};
Percentiles percentiles(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  auto at = [&](double q) {  // linear interpolation, as R's type 7
    const double i = q * double(v.size() - 1);
    const std::size_t lo = std::size_t(std::floor(i)), hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (i - double(lo)) * (v[hi] - v[lo]);
  };
  return {at(0.5), at(0.95), v.back()};
}

struct Outcome {
  std::string engine;
  int steps = 0;
  Percentiles step_ms;
  bool held = false, released = false, finite = true;
  double lift = 0.0, slip_mm = 0.0, max_penetration_mm = 0.0;
  double run_penetration_mm = 0.0;  // the deepest over the whole run, not only the hold
};

// The Bullet world of the pinch scene.
class BulletPinch {
 public:
  explicit BulletPinch(const PinchScene& scene) : scene_(scene) {
    const HandSimModel& model = scene.model;
    const auto& par = model.parameters;
    RigidPose cube_start;
    cube_start.position = scene.script.cube_centre;
    const HandSimState start =
        initial_state(model, scene.skeleton, scene.script.start_root(), cube_start);

    configuration_ = std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(configuration_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    deformable_solver_ = std::make_unique<btDeformableBodySolver>();
    constraint_solver_ = std::make_unique<btDeformableMultiBodyConstraintSolver>();
    constraint_solver_->setDeformableSolver(deformable_solver_.get());
    world_ = std::make_unique<btDeformableMultiBodyDynamicsWorld>(
        dispatcher_.get(), broadphase_.get(), constraint_solver_.get(), configuration_.get(),
        deformable_solver_.get());
    world_->setGravity(bt(par.gravity));
    world_->getWorldInfo().m_gravity = bt(par.gravity);
    // The signed distance to the cube is sampled on a grid: a millimetre resolves the small
    // cube's faces (Bullet's default, 0.25 m, is for metre-sized scenes).
    world_->getWorldInfo().m_sparsesdf.setDefaultVoxelsz(0.001);
    world_->getWorldInfo().m_sparsesdf.Reset();
    world_->setImplicit(true);
    world_->setLineSearch(false);
    // Contacts and anchors by projection in the CG solve: without it (the Lagrange-multiplier
    // path) the implicit solve leaves every free node where it was (measured on a lone tet).
    world_->setUseProjection(true);

    // The floor: a static slab whose top is the floor plane.
    shapes_.push_back(std::make_unique<btBoxShape>(btVector3(1, 0.05, 1)));
    floor_ = add_body(0.0, shapes_.back().get(),
                      btTransform(btQuaternion::getIdentity(),
                                  btVector3(0, btScalar(par.floor_height - 0.05), 0)),
                      kFloor, kCube);
    // Bullet's friction of a pair is the product of its bodies': the cube's 1, so that the
    // floor gives the cube on the floor `friction` and the flesh the skin's `skin_friction`.
    floor_->setFriction(btScalar(par.friction));
    // The cube.
    shapes_.push_back(std::make_unique<btBoxShape>(bt(model.cube_half)));
    cube_ = add_body(model.cube.mass, shapes_.back().get(), bt(start.cube_pose), kCube,
                     kFloor | kFlesh);
    cube_->setFriction(1.0);
    cube_->setActivationState(DISABLE_DEACTIVATION);
    // The bones: kinematic, on their targets.
    shapes_.push_back(std::make_unique<btSphereShape>(0.002));
    for (int b = 0; b < model.bone_count(); ++b) {
      btRigidBody* bone =
          add_body(0.0, shapes_.back().get(), bt(start.bone_pose[std::size_t(b)]), kBones, 0);
      bone->setCollisionFlags(bone->getCollisionFlags() | btCollisionObject::CF_KINEMATIC_OBJECT);
      bone->setActivationState(DISABLE_DEACTIVATION);
      bones_.push_back(bone);
    }

    // The flesh: the model's nodes where the script starts, its masses and tets.
    const int n = model.node_count();
    std::vector<btVector3> x(static_cast<std::size_t>(n));
    std::vector<btScalar> m(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      x[std::size_t(i)] = bt(start.node_position[std::size_t(i)]);
      m[std::size_t(i)] = btScalar(model.node_mass[std::size_t(i)]);
    }
    flesh_ = new btSoftBody(&world_->getWorldInfo(), n, x.data(), m.data());
    std::set<std::pair<int, int>> edges;
    for (const auto& t : model.tets) {
      flesh_->appendTetra(t.nodes[0], t.nodes[1], t.nodes[2], t.nodes[3]);
      for (int a = 0; a < 4; ++a)
        for (int b = a + 1; b < 4; ++b)
          edges.insert(std::minmax(t.nodes[std::size_t(a)], t.nodes[std::size_t(b)]));
    }
    for (const auto& [a, b] : edges) flesh_->appendLink(a, b);
    btSoftBodyHelpers::generateBoundaryFaces(flesh_);
    flesh_->initializeDmInverse();
    flesh_->m_tetraScratches.resize(flesh_->m_tetras.size());
    flesh_->m_tetraScratchesTn.resize(flesh_->m_tetras.size());
    flesh_->m_cfg.kKHR = 1;  // contact hardness with kinematic and rigid bodies
    flesh_->m_cfg.kCHR = 1;
    flesh_->m_cfg.kDF = btScalar(par.skin_friction);  // times the cube's 1
    // Flesh nodes against the cube, as handlab's contacts (SDF_RDN: node-based; SDF_RD alone
    // finds none).
    flesh_->m_cfg.collisions = btSoftBody::fCollision::SDF_RD | btSoftBody::fCollision::SDF_RDN;
    flesh_->getCollisionShape()->setMargin(0.0005);
    flesh_->setActivationState(DISABLE_DEACTIVATION);
    world_->addSoftBody(flesh_, kFlesh, kCube);
    forces_.push_back(std::make_unique<btDeformableGravityForce>(bt(par.gravity)));
    world_->addForce(flesh_, forces_.back().get());
    forces_.push_back(std::make_unique<btDeformableLinearElasticityForce>(
        btScalar(par.flesh.mu()), btScalar(par.flesh.lambda())));
    world_->addForce(flesh_, forces_.back().get());

    // Anchors: each node of a coupling point's tet held to the bone whose coupling weighs on
    // it most (the flesh is a layer one or two tets thick around the capsules: nearly every
    // node is on the skin, so the skin's are anchored too).
    std::map<int, std::pair<double, int>> anchored;  // node -> (weight, bone)
    for (const auto& c : model.coupling)
      for (int a = 0; a < 4; ++a) {
        auto& best = anchored.try_emplace(c.nodes[std::size_t(a)], -1.0, c.bone).first->second;
        if (c.weights(a) > best.first) best = {c.weights(a), c.bone};
      }
    for (const auto& [node, weighted] : anchored)
      flesh_->appendDeformableAnchor(node, bones_[std::size_t(weighted.second)]);
    anchors_ = int(anchored.size());
  }

  ~BulletPinch() {
    for (int i = world_->getNumCollisionObjects() - 1; i >= 0; --i) {
      btCollisionObject* object = world_->getCollisionObjectArray()[i];
      if (btRigidBody* body = btRigidBody::upcast(object)) delete body->getMotionState();
      if (btSoftBody* soft = btSoftBody::upcast(object))
        world_->removeSoftBody(soft);
      else
        world_->removeCollisionObject(object);
      delete object;
    }
  }

  int anchors() const { return anchors_; }

  // One step towards the bones' targets at the time the step reaches.
  // `substeps` internal steps of Bullet's (its demos take 1/240 s for stability).
  void step(const std::vector<RigidPose>& targets, int substeps) {
    for (std::size_t b = 0; b < bones_.size(); ++b)
      bones_[b]->getMotionState()->setWorldTransform(bt(targets[b]));
    const btScalar h = btScalar(scene_.model.parameters.time_step);
    world_->stepSimulation(h, substeps, h / substeps);
  }

  // The scene as handlab's state holds it (bones, cube, nodes), for run_pinch's measures.
  void mirror(HandSimState& s) const {
    for (std::size_t b = 0; b < bones_.size(); ++b) {
      btTransform t;
      bones_[b]->getMotionState()->getWorldTransform(t);
      s.bone_pose[b] = pose(t);
    }
    s.cube_pose = pose(cube_->getWorldTransform());
    for (int i = 0; i < flesh_->m_nodes.size(); ++i)
      s.node_position[std::size_t(i)] = eigen(flesh_->m_nodes[i].m_x);
  }

 private:
  btRigidBody* add_body(double mass, btCollisionShape* shape, const btTransform& at, int group,
                        int mask) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(btScalar(mass), inertia);
    auto* motion = new btDefaultMotionState(at);
    auto* body = new btRigidBody(
        btRigidBody::btRigidBodyConstructionInfo(btScalar(mass), motion, shape, inertia));
    world_->addRigidBody(body, group, mask);
    return body;
  }

  const PinchScene& scene_;
  std::unique_ptr<btSoftBodyRigidBodyCollisionConfiguration> configuration_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btDeformableBodySolver> deformable_solver_;
  std::unique_ptr<btDeformableMultiBodyConstraintSolver> constraint_solver_;
  std::unique_ptr<btDeformableMultiBodyDynamicsWorld> world_;
  std::vector<std::unique_ptr<btCollisionShape>> shapes_;
  std::vector<std::unique_ptr<btDeformableLagrangianForce>> forces_;
  btRigidBody *floor_ = nullptr, *cube_ = nullptr;
  std::vector<btRigidBody*> bones_;
  btSoftBody* flesh_ = nullptr;
  int anchors_ = 0;
};

// The deepest flesh node inside the cube (m), 0 when none is.
double max_penetration(const HandSimModel& model, const HandSimState& s) {
  double deepest = 0.0;
  for (int node : model.surface_nodes) {
    const Eigen::Vector3d q = s.cube_pose.rotation.conjugate() *
                              (s.node_position[std::size_t(node)] - s.cube_pose.position);
    deepest = std::max(deepest, -handlab::sim::box_proximity(model.cube_half, q).distance);
  }
  return deepest;
}

// The Bullet world through the script, measured by run_pinch's rules (PinchMeter).
Outcome run_bullet(const PinchScene& scene, double duration, int substeps) {
  const HandSimModel& model = scene.model;
  const auto& script = scene.script;
  BulletPinch world(scene);
  std::printf("bullet: %d nodes held to the bones by anchors\n", world.anchors());
  RigidPose cube_start;
  cube_start.position = script.cube_centre;
  HandSimState s = initial_state(model, scene.skeleton, script.start_root(), cube_start);
  const double h = model.parameters.time_step;
  const int steps = int(std::ceil(duration / h - 1e-9));
  Outcome out;
  out.engine = "bullet 3.24 (btDeformableMultiBodyDynamicsWorld, implicit), " +
               std::to_string(substeps) + " substep" + (substeps > 1 ? "s" : "");
  std::vector<double> step_ms;
  handlab::sim::PinchMeter meter(model, script);
  for (int i = 0; i < steps; ++i) {
    const double t = (i + 1) * h;
    const auto targets = bone_targets(model, scene.skeleton, script.target(t));
    const auto begin = std::chrono::steady_clock::now();
    world.step(targets, substeps);
    step_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin)
            .count());
    world.mirror(s);
    if (!s.cube_pose.position.allFinite()) {
      out.finite = false;
      break;
    }
    const double deepest = max_penetration(model, s);
    out.run_penetration_mm = std::max(out.run_penetration_mm, 1000 * deepest);
    meter.observe(s, t, deepest);
  }
  handlab::sim::PinchReport report;
  meter.finish(s, duration, max_penetration(model, s) > 0, report);
  out.steps = int(step_ms.size());
  out.step_ms = percentiles(step_ms);
  out.held = out.finite && report.held;
  out.released = out.finite && report.released;
  out.lift = report.lift;
  out.slip_mm = report.slip_mm;
  out.max_penetration_mm = report.max_penetration_mm;
  return out;
}

Outcome run_handlab(const PinchScene& scene, double duration) {
  Outcome out;
  const handlab::sim::PinchReport r = run_pinch(
      scene.model, scene.skeleton, scene.script, {}, duration, [&](const HandSimState& s) {
        out.run_penetration_mm =
            std::max(out.run_penetration_mm, 1000 * max_penetration(scene.model, s));
      });
  out.engine = "handlab (HandSimulator, two threads)";
  out.steps = int(r.step_ms.size());
  out.step_ms = percentiles(r.step_ms);
  out.held = r.held;
  out.released = r.released;
  out.lift = r.lift;
  out.slip_mm = r.slip_mm;
  out.max_penetration_mm = r.max_penetration_mm;
  return out;
}

void print(const Outcome& o, double cube) {
  std::printf(
      "%-58s cube %.0f cm, %d steps: median %.2f ms, p95 %.2f ms, max %.2f ms; %s, lift %.1f "
      "cm, slip %.3f mm, max penetration %.2f mm in the hold, %.2f mm in the run, %s\n",
      o.engine.c_str(), 100 * cube, o.steps, o.step_ms.median, o.step_ms.p95, o.step_ms.max,
      !o.finite ? "DIVERGED"
      : o.held  ? "held"
                : "NOT held",
      100 * o.lift, o.slip_mm, o.max_penetration_mm, o.run_penetration_mm,
      o.released ? "released" : "not released");
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> cubes = {0.01, 0.06};
  double duration = 0.0;
  int substeps = 1;
  std::string json;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--cube" && i + 1 < argc) {
      cubes = {std::atof(argv[++i])};
    } else if (a == "--duration" && i + 1 < argc) {
      duration = std::atof(argv[++i]);
    } else if (a == "--substeps" && i + 1 < argc) {
      substeps = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--json" && i + 1 < argc) {
      json = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: handlab_bullet_pinch [--cube 0.01|0.06] [--duration S] [--substeps N] "
                   "[--json OUT]\n");
      return a == "--help" ? 0 : 2;
    }
  }
  std::string out = "[";
  for (double cube : cubes) {
    const PinchScene scene = handlab::sim::make_pinch_scene(cube);
    const double d = duration > 0 ? duration : scene.script.end;
    for (const Outcome& o : {run_handlab(scene, d), run_bullet(scene, d, substeps)}) {
      print(o, cube);
      char row[1024];
      std::snprintf(row, sizeof row,
                    "%s{\"engine\": \"%s\", \"cube_size_m\": %.3f, \"steps\": %d, \"step_ms\": "
                    "{\"median\": %.4f, \"p95\": %.4f, \"max\": %.4f}, \"finite\": %s, \"held\": "
                    "%s, \"released\": %s, \"lift_m\": %.5f, \"slip_mm\": %.4f, "
                    "\"max_penetration_mm\": %.4f, \"run_penetration_mm\": %.4f}",
                    out.size() > 1 ? ", " : "", o.engine.c_str(), cube, o.steps, o.step_ms.median,
                    o.step_ms.p95, o.step_ms.max, o.finite ? "true" : "false",
                    o.held ? "true" : "false", o.released ? "true" : "false", o.lift, o.slip_mm,
                    o.max_penetration_mm, o.run_penetration_mm);
      out += row;
    }
  }
  out += "]\n";
  if (!json.empty()) std::ofstream(json) << out;
  return 0;
}
