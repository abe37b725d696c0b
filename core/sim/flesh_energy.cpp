#include "core/sim/flesh_energy.h"

#include <algorithm>

#include "core/sim/rotation_extraction.h"

namespace handlab::sim {
namespace {

// Four tets, one in each SIMD lane. A batch past the range's end repeats its last tet with no
// volume.
struct TetBatch {
  Lane4 f[9];           // F, row-major
  Lane4 r[9];           // R, row-major
  Lane4 gradients[12];  // grad N_a, entry 3a + i
  Lane4 volume;
};

// F of tets e, ... (sum over a of (x_a - x_0) grad N_a').
void gather(const HandSimModel& model, const HandSimState& s, std::size_t e, std::size_t end,
            TetBatch& b, bool with_gradients) {
  for (Lane4& v : b.f) v.setZero();
  for (int l = 0; l < kTetBatch; ++l) {
    const std::size_t k = std::min(e + std::size_t(l), end - 1);
    const TetElement& t = model.tets[k];
    const Eigen::Vector3d& x0 = s.node_position[std::size_t(t.nodes[0])];
    for (int a = 1; a < 4; ++a) {
      const Eigen::Vector3d d = s.node_position[std::size_t(t.nodes[std::size_t(a)])] - x0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) b.f[3 * i + j][l] += d[i] * t.gradients(j, a);
    }
    b.volume[l] = e + std::size_t(l) < end ? t.volume : 0.0;
    if (with_gradients)
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) b.gradients[3 * a + i][l] = t.gradients(i, a);
  }
}

// R of tets e, ... from their quaternions.
void rotations(const HandSimState& s, std::size_t e, std::size_t end, TetBatch& b) {
  Lane4 w, x, y, z;
  for (int l = 0; l < kTetBatch; ++l) {
    const Eigen::Quaterniond& q = s.tet_rotation[std::min(e + std::size_t(l), end - 1)];
    w[l] = q.w();
    x[l] = q.x();
    y[l] = q.y();
    z[l] = q.z();
  }
  rotation_matrices(w, x, y, z, b.r);
}

// The strain sym(R'F) - I (xx, yy, zz, xy, xz, yz).
void strain(const TetBatch& b, Lane4 (&e)[6]) {
  auto g = [&](int i, int j) {  // (R'F)_ij
    return b.r[i] * b.f[j] + b.r[3 + i] * b.f[3 + j] + b.r[6 + i] * b.f[6 + j];
  };
  e[0] = g(0, 0) - 1;
  e[1] = g(1, 1) - 1;
  e[2] = g(2, 2) - 1;
  e[3] = 0.5 * (g(0, 1) + g(1, 0));
  e[4] = 0.5 * (g(0, 2) + g(2, 0));
  e[5] = 0.5 * (g(1, 2) + g(2, 1));
}
Lane4 squared_norm(const Lane4 (&e)[6]) {
  return e[0].square() + e[1].square() + e[2].square() +
         2 * (e[3].square() + e[4].square() + e[5].square());
}

// Tets [begin, end): their rotations (polar decomposition of F, from the last), their
// energy, their forces added to `forces` (node unknowns), their terms into `tet_terms`.
double flesh_terms(const HandSimModel& model, HandSimState& s, std::size_t begin, std::size_t end,
                   double scale, double* forces, TetTerms4* tet_terms) {
  const SimParameters& par = model.parameters;
  const double mu = par.flesh.mu(), lambda = par.flesh.lambda();
  const double stiffening = par.stiffening_factor * par.flesh.youngs_modulus;
  const double threshold = par.stiffening_strain;
  const double blend_width = std::max(par.stiffening_blend * threshold, 1e-300);
  const double blend_from = threshold - par.stiffening_blend * threshold;
  Lane4 sum = Lane4::Zero();
  TetBatch b;
  for (std::size_t e = begin; e < end; e += kTetBatch) {
    gather(model, s, e, end, b, true);
    const int count = int(std::min<std::size_t>(kTetBatch, end - e));
    Eigen::Quaterniond* const q[kTetBatch] = {
        &s.tet_rotation[e], &s.tet_rotation[e + std::size_t(std::min(1, count - 1))],
        &s.tet_rotation[e + std::size_t(std::min(2, count - 1))],
        &s.tet_rotation[e + std::size_t(std::min(3, count - 1))]};
    extract_rotations(b.f, q, count);
    rotations(s, e, end, b);
    Lane4 n[6];
    strain(b, n);
    const Lane4 trace = n[0] + n[1] + n[2], squared = squared_norm(n), norm = squared.sqrt();
    // Stiffening beyond a strain threshold: (k V / 2)(|e| - e0)^2, whose stress is
    // k (|e| - e0) e / |e|; its Hessian k V [(e0/|e|) q q' + (1 - e0/|e|) B'B] (q the
    // gradient direction, B the strain map) is positive semidefinite. In the blend band below
    // the threshold the matrix takes k V s(t) q q' (s a smoothstep over the band, 1 at the
    // threshold, where it meets the Hessian above): continuous, so a step from below does not
    // overshoot into the stiff range, and a factor stays a good preconditioner.
    const auto stiff = norm > blend_from;
    const auto beyond = norm > threshold;
    const Lane4 excess = beyond.select(norm - threshold, 0.0);
    const Lane4 safe_norm = stiff.select(norm, 1.0);
    const Lane4 ratio = beyond.select(threshold / safe_norm, 1.0);
    const Lane4 t = ((norm - blend_from) / blend_width).min(1.0);
    const Lane4 k = beyond.select(stiffening * b.volume,
                                  stiff.select(t * t * (3 - 2 * t) * stiffening * b.volume, 0.0));
    sum += b.volume * (mu * squared + 0.5 * lambda * trace.square()) +
           0.5 * stiffening * b.volume * excess.square();
    // stress = 2 mu e + lambda tr(e) I + (stiffening excess / |e|) e, row-major.
    const Lane4 shear = 2 * mu + stiffening * excess / safe_norm;
    const Lane4 stress[9] = {
        shear * n[0] + lambda * trace, shear * n[3], shear * n[4], shear * n[3],
        shear * n[1] + lambda * trace, shear * n[5], shear * n[4], shear * n[5],
        shear * n[2] + lambda * trace};
    const Lane4 e9[9] = {n[0], n[3], n[4], n[3], n[1], n[5], n[4], n[5], n[2]};
    // R stress and R e, row-major.
    Lane4 rs[9], re[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        rs[3 * i + j] = b.r[3 * i] * stress[j] + b.r[3 * i + 1] * stress[3 + j] +
                        b.r[3 * i + 2] * stress[6 + j];
        re[3 * i + j] =
            b.r[3 * i] * e9[j] + b.r[3 * i + 1] * e9[3 + j] + b.r[3 * i + 2] * e9[6 + j];
      }
    const Lane4 q_scale = stiff.select((scale * k * ratio).sqrt() / safe_norm, 0.0);
    const Lane4 force_scale = scale * b.volume;
    // The terms (a batch past the last tet has no volume: no terms).
    TetTerms4& term = tet_terms[e / kTetBatch];
    term.vmu = scale * (b.volume * mu + 0.5 * k * (1.0 - ratio));
    term.vlambda = scale * b.volume * lambda;
    // Times grad N_a: the forces, R grad N_a and the stiffening's rank-one part.
    Lane4 force[12];
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i) {
        const Lane4 &g0 = b.gradients[3 * a], &g1 = b.gradients[3 * a + 1],
                    &g2 = b.gradients[3 * a + 2];
        force[3 * a + i] = force_scale * (rs[3 * i] * g0 + rs[3 * i + 1] * g1 + rs[3 * i + 2] * g2);
        term.rotated[3 * a + i] = b.r[3 * i] * g0 + b.r[3 * i + 1] * g1 + b.r[3 * i + 2] * g2;
        term.q[3 * a + i] = q_scale * (re[3 * i] * g0 + re[3 * i + 1] * g1 + re[3 * i + 2] * g2);
      }
    for (int l = 0; l < count; ++l) {
      const TetElement& t = model.tets[e + std::size_t(l)];
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i) forces[3 * t.nodes[std::size_t(a)] + i] += force[3 * a + i][l];
    }
  }
  return scale * ((sum[0] + sum[1]) + (sum[2] + sum[3]));
}

}  // namespace

double flesh_energy(const HandSimModel& model, const HandSimState& s, std::size_t begin,
                    std::size_t end, double scale) {
  const SimParameters& par = model.parameters;
  const double mu = par.flesh.mu(), lambda = par.flesh.lambda();
  const double stiffening = par.stiffening_factor * par.flesh.youngs_modulus;
  Lane4 sum = Lane4::Zero();
  TetBatch b;
  for (std::size_t e = begin; e < end; e += kTetBatch) {
    gather(model, s, e, end, b, false);
    rotations(s, e, end, b);
    Lane4 n[6];
    strain(b, n);
    const Lane4 trace = n[0] + n[1] + n[2], squared = squared_norm(n);
    const Lane4 excess = (squared.sqrt() - par.stiffening_strain).max(0.0);
    sum += b.volume *
           (mu * squared + 0.5 * lambda * trace.square() + 0.5 * stiffening * excess.square());
  }
  return scale * ((sum[0] + sum[1]) + (sum[2] + sum[3]));
}

// Whole batches to each worker; each worker's forces into its own buffer (worker 0's into the
// gradient), added in worker order.
void add_flesh(const HandSimModel& model, HandSimState& s, NewtonTerms& terms, ThreadPool& pool,
               FleshBuffers& buffers) {
  const int count = int(model.tets.size()), batches = (count + kTetBatch - 1) / kTetBatch;
  const bool hessian = terms.with_hessian;
  const int nodes = model.node_count();
  buffers.forces.resize(std::size_t(pool.workers()));
  buffers.energy.resize(std::size_t(pool.workers()));
  if (hessian) terms.tets.resize(std::size_t(batches));
  pool.run([&](int worker) {
    const auto [first, last] = pool.share(worker, batches);
    const int begin = std::min(kTetBatch * first, count), end = std::min(kTetBatch * last, count);
    double* forces = terms.gradient.data();
    if (worker > 0 && hessian) {
      buffers.forces[std::size_t(worker)].setZero(3 * nodes);
      forces = buffers.forces[std::size_t(worker)].data();
    }
    buffers.energy[std::size_t(worker)] =
        hessian ? flesh_terms(model, s, std::size_t(begin), std::size_t(end), terms.scale, forces,
                              terms.tets.data())
                : flesh_energy(model, s, std::size_t(begin), std::size_t(end), terms.scale);
  });
  for (int worker = 0; worker < pool.workers(); ++worker) {
    terms.energy += buffers.energy[std::size_t(worker)];
    if (worker > 0 && hessian)
      terms.gradient.head(3 * nodes) += buffers.forces[std::size_t(worker)];
  }
}

}  // namespace handlab::sim
