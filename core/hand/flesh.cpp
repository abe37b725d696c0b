#include "core/hand/flesh.h"

#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <unordered_map>

#include <Eigen/Dense>

#include "core/mesh/tetrahedralize.h"

namespace handlab::hand {
namespace {

// Point location in a tet mesh through a uniform grid of tet bounding boxes.
class TetLocator {
 public:
  explicit TetLocator(const mesh::TetMesh& mesh) : mesh_(mesh) {
    Eigen::AlignedBox3d all;
    for (const auto& p : mesh.nodes) all.extend(p);
    origin_ = all.min();
    cell_ = std::cbrt(all.volume() / double(std::max<std::size_t>(mesh.tets.size(), 1))) * 1.5;
    for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
      Eigen::AlignedBox3d box;
      for (int v : mesh.tets[t]) box.extend(mesh.nodes[std::size_t(v)]);
      const auto lo = cell_of(box.min()), hi = cell_of(box.max());
      for (long x = lo[0]; x <= hi[0]; ++x)
        for (long y = lo[1]; y <= hi[1]; ++y)
          for (long z = lo[2]; z <= hi[2]; ++z) grid_[key(x, y, z)].push_back(int(t));
    }
  }

  Eigen::Vector4d barycentric(int tet, const Eigen::Vector3d& p) const {
    const auto& t = mesh_.tets[std::size_t(tet)];
    Eigen::Matrix3d m;
    const Eigen::Vector3d& a = mesh_.nodes[std::size_t(t[0])];
    for (int k = 0; k < 3; ++k) m.col(k) = mesh_.nodes[std::size_t(t[std::size_t(k + 1)])] - a;
    const Eigen::Vector3d w = m.partialPivLu().solve(p - a);
    return Eigen::Vector4d(1.0 - w.sum(), w.x(), w.y(), w.z());
  }

  // The tet containing p (or, when p is outside, the one it is least outside of within
  // `reach`); -1 when none is near.
  int locate(const Eigen::Vector3d& p, Eigen::Vector4d* weights, bool inside_only) const {
    int best = -1;
    double best_score = -1e300;
    for (int ring = 0; ring <= (inside_only ? 0 : 2) && best < 0; ++ring) {
      const auto c = cell_of(p);
      for (long x = c[0] - ring; x <= c[0] + ring; ++x)
        for (long y = c[1] - ring; y <= c[1] + ring; ++y)
          for (long z = c[2] - ring; z <= c[2] + ring; ++z) {
            const auto it = grid_.find(key(x, y, z));
            if (it == grid_.end()) continue;
            for (int t : it->second) {
              const Eigen::Vector4d w = barycentric(t, p);
              const double score = w.minCoeff();
              if (score > best_score) {
                best_score = score;
                best = t;
                *weights = w;
              }
            }
          }
      if (best >= 0 && best_score < -1e-9 && inside_only) best = -1;
    }
    return best;
  }

 private:
  std::array<long, 3> cell_of(const Eigen::Vector3d& p) const {
    const Eigen::Vector3d c = (p - origin_) / cell_;
    return {long(std::floor(c.x())), long(std::floor(c.y())), long(std::floor(c.z()))};
  }
  static long key(long x, long y, long z) {
    return (x * 73856093L) ^ (y * 19349663L) ^ (z * 83492791L);
  }

  const mesh::TetMesh& mesh_;
  Eigen::Vector3d origin_;
  double cell_;
  std::unordered_map<long, std::vector<int>> grid_;
};

// The distal capsule, in units of the bone's radius: its radius and its shift to the back
// (calibrated with the fingertip test: about 1.2 mm of indentation at 1 N).
constexpr double kDistalRadius = 0.55, kDistalShift = 0.35;

bool is_distal(const Skeleton& skeleton, int bone) {
  for (const Bone& b : skeleton.bones)
    if (b.parent == bone) return false;
  return bone > 0;
}

}  // namespace

std::vector<Capsule> bone_capsules(const Skeleton& skeleton, const HandShape& shape) {
  std::vector<Capsule> capsules;
  const BoneFrames rest = forward_kinematics(skeleton, HandPose::rest(skeleton));
  const double hl = shape.length;
  // The palm's metacarpals: from near the carpus to each finger's MCP (in the palm frame).
  for (int f = 1; f < kFingerCount; ++f) {
    const int first = skeleton.bone_index(std::string(finger_name(f)) + "1");
    const Eigen::Vector3d mcp = skeleton.bones[std::size_t(first)].offset;
    const Eigen::Vector3d base(0.55 * mcp.x(), 0.06 * hl, 0.0);
    const double radius = 0.35 * skeleton.bones[std::size_t(first)].radius + 0.01 * hl;
    capsules.push_back({0, base, mcp - 0.03 * hl * (mcp - base).normalized(), radius});
  }
  for (std::size_t b = 1; b < skeleton.bones.size(); ++b) {
    const Bone& bone = skeleton.bones[b];
    // Keep clear of the joints so neighbouring capsules do not overlap much.
    const double trim = 0.25 * bone.radius;
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    double radius = bone.radius;
    if (is_distal(skeleton, int(b))) {
      // The distal phalanx is a slender bone on the nail's side: the pulp under it is what a
      // press on the fingertip compresses (the tip's stiffness depends on its thickness).
      const Eigen::Vector3d palmar = skeleton.dofs[std::size_t(bone.first_dof)]
                                         .axis.cross(Eigen::Vector3d::UnitY())
                                         .normalized();
      offset = -kDistalShift * bone.radius * palmar;
      radius = kDistalRadius * bone.radius;
    }
    capsules.push_back({int(b), offset + Eigen::Vector3d(0, trim, 0),
                        offset + Eigen::Vector3d(0, bone.length - trim, 0), radius});
  }
  (void)rest;
  return capsules;
}

std::vector<Eigen::Vector3d> embedded_positions(const EmbeddedSurface& surface,
                                                const mesh::TetMesh& tets,
                                                const std::vector<Eigen::Vector3d>& nodes) {
  std::vector<Eigen::Vector3d> out(surface.tet.size());
  for (std::size_t v = 0; v < out.size(); ++v) {
    const auto& t = tets.tets[std::size_t(surface.tet[v])];
    const Eigen::Vector4d& w = surface.barycentric[v];
    out[v] = w[0] * nodes[std::size_t(t[0])] + w[1] * nodes[std::size_t(t[1])] +
             w[2] * nodes[std::size_t(t[2])] + w[3] * nodes[std::size_t(t[3])];
  }
  return out;
}

HandFlesh build_flesh(const Skeleton& skeleton, const HandShape& shape,
                      const FleshOptions& options) {
  int level = 1;
  if (options.resolution == 4)
    level = 2;
  else if (options.resolution == 16)
    level = 3;
  else if (options.resolution != 1)
    throw std::invalid_argument("flesh resolution must be 1, 4 or 16");

  HandFlesh flesh;
  flesh.skin = build_skin(skeleton, shape, level);
  mesh::TetrahedralizeOptions tet_options;
  tet_options.max_radius_edge = 4.0;  // the kept boundary (-Y) bounds quality anyway
  tet_options.min_dihedral_deg = 0.0;
  flesh.tets = mesh::tetrahedralize(flesh.skin.surface, tet_options);
  flesh.quality = mesh::tet_quality(flesh.tets);
  const TetLocator locator(flesh.tets);

  // Coupling points: sample each capsule's cylinder, group the samples by tet.
  flesh.capsules = bone_capsules(skeleton, shape);
  const BoneFrames rest = forward_kinematics(skeleton, HandPose::rest(skeleton));
  for (const Capsule& capsule : flesh.capsules) {
    const Eigen::Vector3d axis = capsule.b - capsule.a;
    const double length = axis.norm();
    const Eigen::Vector3d d = axis / length;
    const Eigen::Vector3d u = d.unitOrthogonal(), v = d.cross(u);
    const int along = std::max(2, int(std::ceil(length / options.capsule_sample_spacing)));
    const int around = std::max(
        8, int(std::ceil(2 * std::numbers::pi * capsule.radius / options.capsule_sample_spacing)));
    const double area = 2 * std::numbers::pi * capsule.radius * length / double(along * around);
    std::map<int, std::pair<double, Eigen::Vector3d>>
        per_tet;  // tet -> (area, area-weighted local sum)
    for (int i = 0; i < along; ++i)
      for (int j = 0; j < around; ++j) {
        const double angle = 2 * std::numbers::pi * (j + 0.5 * (i % 2)) / around;
        const Eigen::Vector3d local = capsule.a + (i + 0.5) / along * axis +
                                      capsule.radius * (std::cos(angle) * u + std::sin(angle) * v);
        const Eigen::Vector3d world = bone_point(rest, capsule.bone, local);
        Eigen::Vector4d w;
        const int tet = locator.locate(world, &w, true);
        if (tet < 0) continue;  // the capsule pokes out of the flesh here
        // Eigen vectors are not zeroed on construction: start each tet's sum explicitly.
        auto& entry = per_tet.try_emplace(tet, 0.0, Eigen::Vector3d::Zero()).first->second;
        entry.first += area;
        entry.second += area * local;
      }
    for (const auto& [tet, entry] : per_tet) {
      CouplingPoint point;
      point.bone = capsule.bone;
      point.tet = tet;
      point.area = entry.first;
      point.local = entry.second / entry.first;
      point.barycentric = locator.barycentric(tet, bone_point(rest, capsule.bone, point.local));
      flesh.coupling.push_back(point);
    }
  }

  // The render surface: one subdivision level finer than the flesh's boundary.
  mesh::PolyMesh finer = flesh.skin.cage;
  for (int l = 0; l <= level; ++l) finer = mesh::catmull_clark(finer);
  const mesh::SurfaceMesh render = mesh::triangulate(finer);
  flesh.render.triangles = render.triangles;
  for (const auto& p : render.vertices) {
    Eigen::Vector4d w = Eigen::Vector4d::Zero();
    const int tet = locator.locate(p, &w, false);
    if (tet < 0) throw std::runtime_error("flesh: a render vertex lies far outside the tets");
    flesh.render.tet.push_back(tet);
    flesh.render.barycentric.push_back(w);
  }
  return flesh;
}

}  // namespace handlab::hand
