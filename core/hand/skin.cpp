#include "core/hand/skin.h"

#include <array>
#include <cmath>
#include <stdexcept>

namespace handlab::hand {
namespace {

constexpr int kColumns = 12, kRows = 2, kLayers = 4, kRingSize = 6;
constexpr double kCageScale = 1.2;  // Catmull-Clark pulls the surface inside its cage
constexpr double kCorner = 0.78;    // cage corners drawn in, for round cross-sections

// The 6 boundary points of a 3 x 2 patch in ring order, as (u, v): u in {-1, 0, 1}
// across the finger, v in {-1, 1} dorsal/palmar.
constexpr std::array<std::array<int, 2>, kRingSize> kRing = {
    {{-1, -1}, {0, -1}, {1, -1}, {1, 1}, {0, 1}, {-1, 1}}};
using Ring = std::array<int, kRingSize>;

class CageBuilder {
 public:
  CageBuilder(const Skeleton& skeleton, const HandShape& shape, double tip_extension)
      : s_(skeleton),
        shape_(shape),
        tip_extension_(tip_extension),
        frames_(forward_kinematics(skeleton, HandPose::rest(skeleton))) {}

  mesh::PolyMesh build() {
    build_palm();
    for (int f = 1; f < kFingerCount; ++f) build_finger(f);
    build_thumb();
    return compact();
  }

 private:
  int add_vertex(const Eigen::Vector3d& p,
                 const std::vector<std::pair<int, double>>& bone_weights) {
    vertices_.push_back(p);
    Eigen::RowVectorXd w = Eigen::RowVectorXd::Zero(Eigen::Index(s_.bones.size()));
    for (const auto& [bone, weight] : bone_weights) w(bone) += weight;
    weights_.push_back(w);
    return int(vertices_.size()) - 1;
  }
  void quad(int a, int b, int c, int d) { faces_.push_back({a, b, c, d}); }
  int bone(int finger, int segment) const { return 1 + 3 * finger + segment; }

  double finger_width(int f) const {
    const double hl = shape_.length;
    double w = shape_.fingers[std::size_t(f)].width * hl * shape_.tissue;
    if (f == 0) return w;
    // Leave a gap to the neighbours at the knuckles.
    const double hb = shape_.hand_breadth();
    for (int g : {f - 1, f + 1}) {
      if (g < 1 || g >= kFingerCount) continue;
      const double spacing = std::abs(shape_.fingers[std::size_t(f)].base_across -
                                      shape_.fingers[std::size_t(g)].base_across) *
                             hb;
      w = std::min(w, 0.8 * spacing);
    }
    return w;
  }

  // Palm grid vertex; columns run radial to ulnar, rows dorsal to palmar, layers proximal
  // to distal (the last at the knuckles).
  Eigen::Vector3d palm_point(int c, int r, int l) const {
    const double hl = shape_.length, side = shape_.left ? -1.0 : 1.0;
    const int finger = 1 + c / 3, local = c % 3;
    // Knuckle layer: the fingers' base rings.
    auto knuckle = [&](int f, int lc) {
      const FingerProportions& p = shape_.fingers[std::size_t(f)];
      const double w = finger_width(f), h = 0.86 * w;
      const double u = 1.0 - lc;  // +1 radial edge, -1 ulnar edge
      const double v = 2.0 * r - 1.0;
      const double corner = (std::abs(u) > 0.5 && std::abs(v) > 0.5) ? kCorner : 1.0;
      return Eigen::Vector3d(
          side * (p.base_across * shape_.hand_breadth() + kCageScale * corner * u * 0.5 * w),
          p.base_along * hl, kCageScale * corner * v * 0.5 * h);
    };
    Eigen::Vector3d top = knuckle(finger, local);
    if (l == kLayers - 1) return top;
    // Proximal layers: the palm narrows towards the wrist and thickens in the middle; the
    // radial column bulges for the thenar eminence.
    static constexpr double kY[kLayers - 1] = {-0.03, 0.14, 0.29};
    static constexpr double kWidth[kLayers - 1] = {0.76, 0.9, 0.97};
    static constexpr double kThenar[kLayers - 1] = {0.0, 0.03, 0.0};
    const double t = shape_.palm_thickness * hl;
    Eigen::Vector3d p = top;
    p.x() *= kWidth[l];
    if (c == 0) p.x() += side * kThenar[l] * shape_.hand_breadth();
    if (c == kColumns - 1) p.x() -= side * 0.03 * shape_.hand_breadth();
    p.y() = kY[l] * hl;
    const double dorsal = -0.42 * t, palmar = 0.58 * t;
    p.z() = r == 0 ? dorsal : palmar;
    if (c == 0 || c == kColumns - 1)
      p.x() -= side * (c == 0 ? 1 : -1) * 0.012 * hl;  // round the edges
    return p;
  }

  void build_palm() {
    for (int l = 0; l < kLayers; ++l)
      for (int r = 0; r < kRows; ++r)
        for (int c = 0; c < kColumns; ++c) {
          const bool knuckle = l == kLayers - 1;
          const int finger = 1 + c / 3;
          std::vector<std::pair<int, double>> w = {{0, 1.0}};
          if (knuckle) w = {{0, 0.5}, {bone(finger, 0), 0.5}};
          grid_[l][r][c] = add_vertex(palm_point(c, r, l), w);
        }
    // Side walls: the ring around each layer is the boundary of the 12 x 2 grid.
    std::vector<std::array<int, 2>> ring;  // (c, r)
    for (int c = 0; c < kColumns; ++c) ring.push_back({c, 0});
    for (int c = kColumns - 1; c >= 0; --c) ring.push_back({c, 1});
    for (int l = 0; l + 1 < kLayers; ++l) {
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const auto a = ring[i], b = ring[(i + 1) % ring.size()];
        // The thumb leaves from the radial wall (column 0) between layers 0 and 2.
        if (a[0] == 0 && b[0] == 0 && l <= 1) continue;
        quad(grid_[l][a[1]][a[0]], grid_[l][b[1]][b[0]], grid_[l + 1][b[1]][b[0]],
             grid_[l + 1][a[1]][a[0]]);
      }
    }
    // Wrist cap and the web between the fingers on the knuckle layer.
    for (int r = 0; r + 1 < kRows; ++r)
      for (int c = 0; c + 1 < kColumns; ++c) {
        quad(grid_[0][r][c], grid_[0][r][c + 1], grid_[0][r + 1][c + 1], grid_[0][r + 1][c]);
        if (c % 3 == 2) {
          const int l = kLayers - 1;
          quad(grid_[l][r][c], grid_[l][r][c + 1], grid_[l][r + 1][c + 1], grid_[l][r + 1][c]);
        }
      }
  }

  // A tube of rings closed by a 2 x 1 cap; ring 0 is given (the palm patch's boundary).
  // The cap is the last ring pushed to the tip apex: its middle edge crosses the tip.
  void build_tube(std::vector<Ring> rings, const Eigen::Vector3d& apex, const Eigen::Vector3d& axis,
                  const std::vector<std::pair<int, double>>& cap_weights) {
    const Ring& before = rings.back();
    Ring cap;
    for (int j = 0; j < kRingSize; ++j) {
      const Eigen::Vector3d p = vertices_[std::size_t(before[std::size_t(j)])];
      const double u = kRing[std::size_t(j)][0];
      // Corners shrink towards the apex; the middle pair becomes the tip.
      const Eigen::Vector3d centre_line = apex - axis * 0.0;
      const Eigen::Vector3d radial = p - (p - apex).dot(axis) * axis - apex;
      const double scale = u == 0 ? 0.55 : 0.5;
      cap[std::size_t(j)] = add_vertex(
          centre_line + scale * radial - (u == 0 ? 0.0 : 0.25) * radial.norm() * axis, cap_weights);
    }
    rings.push_back(cap);
    for (std::size_t k = 0; k + 1 < rings.size(); ++k)
      for (int j = 0; j < kRingSize; ++j)
        quad(rings[k][std::size_t(j)], rings[k][std::size_t((j + 1) % kRingSize)],
             rings[k + 1][std::size_t((j + 1) % kRingSize)], rings[k + 1][std::size_t(j)]);
    // Ring positions 0..5 are (-1,-1) (0,-1) (1,-1) (1,1) (0,1) (-1,1): two quads close it.
    quad(cap[0], cap[1], cap[4], cap[5]);
    quad(cap[1], cap[2], cap[3], cap[4]);
  }

  Ring make_ring(const Eigen::Vector3d& centre, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                 double ra, double rb, const std::vector<std::pair<int, double>>& w) {
    Ring ring;
    for (int j = 0; j < kRingSize; ++j) {
      const double u = kRing[std::size_t(j)][0], v = kRing[std::size_t(j)][1];
      const double corner = (u != 0 && v != 0) ? kCorner : 1.0;
      ring[std::size_t(j)] =
          add_vertex(centre + kCageScale * corner * (u * ra * a + v * rb * b), w);
    }
    return ring;
  }

  void build_finger(int f) {
    const double side = shape_.left ? -1.0 : 1.0;
    const int l = kLayers - 1;
    const int c0 = 3 * (f - 1);
    // Ring 0: the patch boundary, u radial (+1 at the patch's first column), v palmar.
    Ring base;
    for (int j = 0; j < kRingSize; ++j)
      base[std::size_t(j)] =
          grid_[l][(kRing[std::size_t(j)][1] + 1) / 2][c0 + 1 - kRing[std::size_t(j)][0]];
    std::vector<Ring> rings = {base};
    const double w = finger_width(f), h = 0.86 * w;
    // (segment, fraction along it, width factor)
    const std::array<std::array<double, 3>, 4> stations = {
        {{1, 0.0, 0.94}, {2, 0.0, 0.86}, {2, 0.62, 0.84}, {2, 1.0, 0.0}}};
    for (std::size_t k = 0; k + 1 < stations.size(); ++k) {
      const int segment = int(stations[k][0]);
      const int b = bone(f, segment);
      const Eigen::Vector3d centre = bone_point(
          frames_, b, Eigen::Vector3d(0, stations[k][1] * s_.bones[std::size_t(b)].length, 0));
      const Eigen::Matrix3d& r = frames_.rotation[std::size_t(b)];
      std::vector<std::pair<int, double>> weights = {{b, 1.0}};
      if (stations[k][1] == 0.0) weights = {{b, 0.5}, {b - 1, 0.5}};
      rings.push_back(make_ring(centre, side * r.col(0), r.col(2), 0.5 * w * stations[k][2],
                                0.5 * h * stations[k][2], weights));
    }
    const int tip = bone(f, 2);
    const Eigen::Vector3d apex = bone_point(
        frames_, tip, Eigen::Vector3d(0, s_.bones[std::size_t(tip)].length + tip_extension_, 0));
    build_tube(rings, apex, frames_.rotation[std::size_t(tip)].col(1), {{tip, 1.0}});
  }

  void build_thumb() {
    // Ring 0: the radial wall patch (column 0, layers 0..2), u along +y, v palmar.
    Ring base;
    for (int j = 0; j < kRingSize; ++j)
      base[std::size_t(j)] =
          grid_[1 + kRing[std::size_t(j)][0]][(kRing[std::size_t(j)][1] + 1) / 2][0];
    std::vector<Ring> rings = {base};
    Eigen::Vector3d a(0, 1, 0), b(0, 0, 1);
    const Eigen::Vector3d patch_centre =
        0.5 * (vertices_[std::size_t(grid_[1][0][0])] + vertices_[std::size_t(grid_[1][1][0])]);
    const double w = finger_width(0), h = 0.9 * w;
    const std::array<std::array<double, 3>, 4> stations = {
        {{1, 0.0, 0.96}, {2, 0.0, 0.9}, {2, 0.62, 0.84}, {2, 1.0, 0.0}}};
    // Leave the thenar along the wall's normal, then follow a cubic Hermite curve that
    // arrives at the MCP along the metacarpal, ring planes perpendicular to its tangent.
    {
      const double side = shape_.left ? -1.0 : 1.0;
      const Eigen::Vector3d normal(side, 0, 0);
      const Eigen::Vector3d mcp = frames_.origin[std::size_t(bone(0, 1))];
      const Eigen::Vector3d mcp_axis = frames_.rotation[std::size_t(bone(0, 0))].col(1);
      const double half_y =
          0.5 *
          (vertices_[std::size_t(grid_[2][0][0])] - vertices_[std::size_t(grid_[0][0][0])]).norm();
      const double half_z =
          0.5 *
          (vertices_[std::size_t(grid_[1][1][0])] - vertices_[std::size_t(grid_[1][0][0])]).norm();
      const Eigen::Vector3d p0 = patch_centre + 0.025 * shape_.length * normal;
      const double reach = (mcp - p0).norm();
      auto curve = [&](double t, Eigen::Vector3d* tangent) {
        const double h00 = 2 * t * t * t - 3 * t * t + 1, h10 = t * t * t - 2 * t * t + t;
        const double h01 = -2 * t * t * t + 3 * t * t, h11 = t * t * t - t * t;
        *tangent = ((6 * t * t - 6 * t) * p0 + (3 * t * t - 4 * t + 1) * reach * normal +
                    (-6 * t * t + 6 * t) * mcp + (3 * t * t - 2 * t) * reach * mcp_axis)
                       .normalized();
        return Eigen::Vector3d(h00 * p0 + h10 * reach * normal + h01 * mcp +
                               h11 * reach * mcp_axis);
      };
      const std::array<std::array<double, 3>, 2> steps = {
          {{0.0, 0.6, 0.7}, {0.5, 0.5, 0.3}}};  // t, size, palm weight
      for (const auto& step : steps) {
        Eigen::Vector3d tangent;
        const Eigen::Vector3d centre = curve(step[0], &tangent);
        a = (a - a.dot(tangent) * tangent).normalized();
        b = (b - b.dot(tangent) * tangent - b.dot(a) * a).normalized();
        const double ra = step[0] == 0.0 ? step[1] * half_y / kCageScale : step[1] * w;
        const double rb = step[0] == 0.0 ? step[1] * half_z / kCageScale : step[1] * h;
        rings.push_back(
            make_ring(centre, a, b, ra, rb, {{0, step[2]}, {bone(0, 0), 1.0 - step[2]}}));
      }
    }
    for (std::size_t k = 0; k + 1 < stations.size(); ++k) {
      const int bone_index = bone(0, int(stations[k][0]));
      const Eigen::Vector3d centre = bone_point(
          frames_, bone_index,
          Eigen::Vector3d(0, stations[k][1] * s_.bones[std::size_t(bone_index)].length, 0));
      const Eigen::Vector3d axis = frames_.rotation[std::size_t(bone_index)].col(1);
      // Parallel transport of the patch axes along the thumb: no twist between rings.
      a = (a - a.dot(axis) * axis).normalized();
      b = (b - b.dot(axis) * axis - b.dot(a) * a).normalized();
      std::vector<std::pair<int, double>> weights = {{bone_index, 1.0}};
      if (stations[k][1] == 0.0) weights = {{bone_index, 0.5}, {bone_index - 1, 0.5}};
      rings.push_back(
          make_ring(centre, a, b, 0.5 * w * stations[k][2], 0.5 * h * stations[k][2], weights));
    }
    const int tip = bone(0, 2);
    const Eigen::Vector3d apex = bone_point(
        frames_, tip, Eigen::Vector3d(0, s_.bones[std::size_t(tip)].length + tip_extension_, 0));
    build_tube(rings, apex, frames_.rotation[std::size_t(tip)].col(1), {{tip, 1.0}});
  }

  // Drops vertices no face uses (the patch centres the tubes replaced).
  mesh::PolyMesh compact() {
    std::vector<int> remap(vertices_.size(), -1);
    mesh::PolyMesh out;
    for (const auto& face : faces_)
      for (int v : face) remap[std::size_t(v)] = 0;
    std::vector<Eigen::RowVectorXd> kept_weights;
    for (std::size_t v = 0; v < vertices_.size(); ++v) {
      if (remap[v] < 0) continue;
      remap[v] = int(out.vertices.size());
      out.vertices.push_back(vertices_[v]);
      kept_weights.push_back(weights_[v]);
    }
    for (auto face : faces_) {
      for (int& v : face) v = remap[std::size_t(v)];
      out.faces.push_back(face);
    }
    out.attributes.resize(Eigen::Index(kept_weights.size()), Eigen::Index(s_.bones.size()));
    for (std::size_t v = 0; v < kept_weights.size(); ++v)
      out.attributes.row(Eigen::Index(v)) = kept_weights[v];
    return out;
  }

  const Skeleton& s_;
  const HandShape& shape_;
  double tip_extension_;
  BoneFrames frames_;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Eigen::RowVectorXd> weights_;
  std::vector<std::vector<int>> faces_;
  int grid_[kLayers][kRows][kColumns] = {};
};

HandSkin build_with_extension(const Skeleton& skeleton, const HandShape& shape, int subdivisions,
                              double extension) {
  HandSkin skin;
  skin.cage = CageBuilder(skeleton, shape, extension).build();
  if (!mesh::orient_outward(skin.cage))
    throw std::runtime_error("hand skin: the cage is not a closed manifold");
  mesh::PolyMesh fine = skin.cage;
  for (int level = 0; level < subdivisions; ++level) fine = mesh::catmull_clark(fine);
  skin.surface = mesh::triangulate(fine);
  skin.weights = fine.attributes;
  skin.measured_length = 0.0;
  for (const auto& v : skin.surface.vertices)
    skin.measured_length = std::max(skin.measured_length, v.y());
  return skin;
}

}  // namespace

HandSkin build_skin(const Skeleton& skeleton, const HandShape& shape, int subdivisions) {
  if (subdivisions < 0 || subdivisions > 4)
    throw std::invalid_argument("hand skin: subdivisions must be 0 to 4");
  // The fingertip pads reach past the distal bone's end by whatever makes the measured hand
  // length (wrist crease to middle fingertip) equal the requested one.
  double extension = 0.0;
  HandSkin skin = build_with_extension(skeleton, shape, subdivisions, extension);
  for (int iteration = 0; iteration < 8 && std::abs(skin.measured_length - shape.length) > 1e-6;
       ++iteration) {
    extension += (shape.length - skin.measured_length) / 0.6;
    skin = build_with_extension(skeleton, shape, subdivisions, extension);
  }
  return skin;
}

std::vector<Eigen::Vector3d> skin_vertices(const Skeleton& skeleton, const HandSkin& skin,
                                           const HandPose& pose) {
  const BoneFrames rest = forward_kinematics(skeleton, HandPose::rest(skeleton));
  const BoneFrames posed = forward_kinematics(skeleton, pose);
  std::vector<Eigen::Matrix3d> r(skeleton.bones.size());
  std::vector<Eigen::Vector3d> t(skeleton.bones.size());
  for (std::size_t b = 0; b < skeleton.bones.size(); ++b) {
    r[b] = posed.rotation[b] * rest.rotation[b].transpose();
    t[b] = posed.origin[b] - r[b] * rest.origin[b];
  }
  std::vector<Eigen::Vector3d> out(skin.surface.vertices.size(), Eigen::Vector3d::Zero());
  for (std::size_t v = 0; v < out.size(); ++v)
    for (std::size_t b = 0; b < skeleton.bones.size(); ++b) {
      const double w = skin.weights(Eigen::Index(v), Eigen::Index(b));
      if (w != 0.0) out[v] += w * (r[b] * skin.surface.vertices[v] + t[b]);
    }
  return out;
}

}  // namespace handlab::hand
